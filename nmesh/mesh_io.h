// nmesh/mesh_io.h — writing and reading triangle meshes (PLY, OBJ, OFF), and writing any file
// atomically.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "nmesh/indexed_mesh.h"

namespace nmesh {

// Writes a file so that `path` is either left untouched or replaced by the complete new content:
// `body` writes into a binary stream on a temporary file in the same directory,
// "<path>.tmp-<pid>-<counter>"; once body has returned and the stream has been flushed to the
// operating system without error, the temporary is renamed over `path` (atomic on POSIX).
// On any failure (body throws, a write fails, the rename fails) the temporary is removed.
// Throws IoError naming `path` (missing directory, cannot create, write or rename failure);
// an exception thrown by `body` is rethrown unchanged after the clean-up.
// The data is flushed to the operating system, not fsynced: a system crash may lose it.
// A `path` that exists and is neither a regular file nor a directory (a device such as /dev/null
// or /dev/stdout, a pipe) is written in place instead: a rename would replace the device itself.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& body);

// Checks, creating nothing, what write_file_atomically would refuse at once: an empty path, a
// parent directory that is missing, not a directory or not writable, a path naming a directory
// (the directory is not checked for a device or a pipe, which is written in place).
// Throws the same IoError. For callers that want to fail before long work, not after it.
void check_output_location(const std::string& path);
// check_output_location, and the mesh format of the extension as write_mesh requires it.
void check_mesh_output(const std::string& path);

struct MeshWriteOptions {
    // PLY only: ASCII instead of the default binary_little_endian.
    bool ply_ascii = false;
    // Per-vertex colours (red, green, blue), empty or one per vertex. Written as uchar
    // red/green/blue vertex properties in PLY and as an "r g b 255" COFF vertex colour in OFF;
    // OBJ has no standard vertex colour, so they are not written there.
    std::vector<std::array<std::uint8_t, 3>> colors;
};

// Writes `mesh` to `path`, the format chosen by the extension (case-insensitive): .ply, .obj or
// .off; anything else is an IoError (nothing is created). Written through write_file_atomically.
// Coordinates in text formats are the shortest decimal text that reads back as the same float,
// so every format round-trips positions bit for bit through read_mesh.
// PLY faces are "list uchar int vertex_indices"; OBJ indices are 1-based.
// Preconditions, checked (ParameterError, nothing written): every coordinate finite; every
// triangle index < positions.size() <= 2^31 - 1; colors empty or colors.size() == positions.size().
// O(vertices + triangles).
void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& options = {});

// Reads a mesh: PLY (any encoding; faces from the "vertex_indices" or "vertex_index" list of the
// "face" element, any integer types), OBJ ("f" corners v, v/vt, v/vt/vn or v//vn; negative indices
// relative to the vertices above), OFF; also the point formats of read_points, which give a mesh
// without triangles. Polygons are fan-triangulated from their first corner: (c0, c(i), c(i+1)).
// Vertices are kept in file order, including unreferenced ones.
// Throws IoError as read_points does, and also for a face index out of range, a face with fewer
// than 3 corners, a non-finite vertex coordinate, or more than 2^32 - 1 vertices.
// O(file size).
IndexedMesh read_mesh(const std::string& path);

}  // namespace nmesh
