// nmesh/io.h — reading point clouds and meshes, writing meshes, and writing any file atomically.
//
// Reading points (and the vertices and faces under them) from files.
//
// Formats, chosen by the file's extension (case-insensitive):
//   .ply                     PLY 1.0: ascii, binary_little_endian, binary_big_endian
//   .xyz .txt .pts .csv      text, one point per line
//   .obj                     Wavefront OBJ ("v" lines are the points)
//   .off                     Object File Format (ASCII)
// Any other extension: the first bytes decide ("ply" + line break -> PLY, "OFF"-style keyword ->
// OFF); otherwise the file is refused as an unknown format.
//
// PLY. The x, y, z properties of the element named "vertex" are the points; they may have any PLY
// numeric type (char uchar short ushort int uint float double, or int8 uint8 int16 uint16 int32
// uint32 float32 float64) and are converted to float (doubles beyond the float range become
// infinite, so they count as non-finite). Every other property and element is skipped, including
// list properties (also inside the vertex element, before or after x, y, z) and elements before
// the vertex element. "comment" and "obj_info" header lines are ignored. In ASCII bodies every
// element record is one line; blank lines are ignored. Data after the last declared record is an
// error in both encodings (trailing whitespace excepted).
//
// Text (.xyz .txt .pts .csv). One point per line: the first three numbers, separated by spaces,
// tabs or commas; further columns are ignored unread. "#" starts a comment that runs to the end of
// the line; blank lines are skipped; CRLF line ends and a UTF-8 byte-order mark are accepted. A
// line with fewer than three numbers, or with a token among its first three that is not a number,
// is an error naming the line. In a .pts file only, a first data line holding exactly one integer
// (the Leica PTS point count) is skipped without being checked. A header row such as "x,y,z" is
// not accepted.
//
// OBJ. "v x y z [...]" lines are the vertices; "f" lines are faces whose corners may be written
// v, v/vt, v/vt/vn or v//vn, with negative indices counting back from the latest vertex. A face
// may only use vertices defined above it. Every other line is ignored.
//
// OFF. Header keyword OFF (also COFF, NOFF, CNOFF, STOFF...; the counts may follow on the same
// line), "nv nf ne", then nv vertex lines (extra columns such as colours ignored) and nf face
// lines "n i0 ... i(n-1) [colour]". "#" comments and blank lines are skipped. Binary OFF is refused.
//
// Decimal text is read correctly rounded to float in every text format ("nan", "inf", "infinity"
// accepted; values beyond the float range become infinite). Non-finite coordinates (NaN, +-Inf, in
// any format) are dropped by read_points and counted in PointReadReport::non_finite_dropped.
//
// Errors: every problem is an nmesh::IoError whose one-line message starts with the path and says
// what is wrong, with the line number for text or the byte offset for binary data. Declared counts
// are checked against the file size before anything is allocated on their word.
//
// Cost: one pass over the file through a 1 MiB buffer (grown only for a single binary record
// larger than that), or, for a binary PLY whose vertex element is exactly float x, y, z in the
// machine's byte order, one read of the body straight into the result. Memory: the result
// (12 bytes per point) plus the buffer. An unreadable file is reported with the system's reason.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/metrics.h"
#include "nmesh/point_cloud.h"
#include "nmesh/vec3.h"

namespace nmesh {

// ---- Reading points -----------------------------------------------------------------------------
// What read_points found, for the caller to print (for example a warning about dropped points).
struct PointReadReport {
    // "ply ascii", "ply binary_little_endian", "ply binary_big_endian", "xyz", "obj" or "off".
    std::string format;
    std::uint64_t points_read = 0;         // points returned (after dropping)
    std::uint64_t non_finite_dropped = 0;  // points dropped because a coordinate was NaN or Inf
};

// Reads the points of the file at `path`. Points keep the file's order.
// Throws IoError (see above). O(file size).
PointCloud read_points(const std::string& path, PointReadReport* report = nullptr);

// One element of a PLY header.
struct PlyElementInfo {
    std::string name;
    std::uint64_t count = 0;
    std::vector<std::string> properties;  // as declared: "float x", "list uchar int vertex_indices"
};

// A summary of a file, for `nmesh info`.
struct FileInfo {
    std::string format;                    // "ply", "xyz", "obj" or "off"
    std::string encoding;                  // PLY: "ascii", "binary_little_endian" or "binary_big_endian"; else "text"
    std::uint64_t file_size = 0;           // bytes
    std::vector<PlyElementInfo> elements;  // PLY header elements in file order; empty otherwise
    std::uint64_t points = 0;              // finite points, as read_points would return
    std::uint64_t non_finite = 0;          // points with a NaN or Inf coordinate
    std::uint64_t faces = 0;               // faces in the file (0 when it has none)
    BoundingBox bounds;                    // of the finite points (empty if there are none)
    // When the file holds faces: the topology of the mesh they make, fan-triangulated as read_mesh
    // does (see mesh_topology in metrics.h; non-finite coordinates allowed). Empty when there are
    // none, or when they do not make a mesh (a face with fewer than 3 corners, an index out of
    // range...): then topology_error holds the error reading them gave, as read_mesh throws it.
    std::optional<MeshTopology> topology;
    std::string topology_error;
};

// Reads the file at `path` completely (so every error read_points reports is reported here too)
// and summarises it, the topology of its faces included. Throws IoError, only where read_points
// would. O(file size) and O(F log F) for F faces; the faces are held while their topology is
// computed. A file whose faces do not make a mesh is read twice, the second time without them.
FileInfo inspect_file(const std::string& path);

// ---- Lower level: the vertices and faces of a file as stored; read_mesh builds on this. ----

enum class ReadFaces : bool { no = false, yes = true };

// Everything the readers take from one file, in file order, nothing dropped.
struct FileGeometry {
    std::string format;                    // as FileInfo::format
    std::string encoding;                  // as FileInfo::encoding
    std::vector<PlyElementInfo> elements;  // PLY only
    std::vector<Vec3> positions;           // every vertex/point, non-finite ones included
    std::uint64_t face_count = 0;          // faces in the file, counted even when not read
    // Filled only with ReadFaces::yes: polygon f is
    // face_indices[face_offsets[f] .. face_offsets[f + 1]). face_offsets has face_count + 1
    // entries (none when face_count is 0). Every polygon has at least 3 corners and every index
    // is < positions.size().
    std::vector<std::size_t> face_offsets;
    std::vector<std::uint32_t> face_indices;
};

// Reads the file at `path`; with ReadFaces::yes also its faces (PLY: the "vertex_indices" or
// "vertex_index" list of the element "face"; indices of any integer type), checking every index.
// With ReadFaces::yes a file with more than 2^32 - 1 vertices is refused (32-bit indices).
// Throws IoError. O(file size).
FileGeometry read_geometry(const std::string& path, ReadFaces faces);

// ---- Writing and reading meshes (PLY, OBJ, OFF) ----------------------------------------------------

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
// Preconditions, checked, nothing written: every coordinate finite, every triangle index <
// positions.size() <= 2^31 - 1 (else InputError, the mesh being unwritable); colors empty or
// colors.size() == positions.size() (else ParameterError).
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
