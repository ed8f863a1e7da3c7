// nmesh/io/format_readers.h — one reader per file format, behind read_geometry (point_reader.cpp).
// Each appends the positions (and, when asked, the faces) of the file to `g` and throws IoError
// naming the file and the place of the problem.
#pragma once

#include "nmesh/io.h"
#include "nmesh/io/input_file.h"

namespace nmesh::io_detail {

void read_ply(InputFile& in, ReadFaces faces, FileGeometry& g);
// `pts`: a .pts file, whose first line may be a point count.
void read_xyz(InputFile& in, bool pts, FileGeometry& g);
void read_obj(InputFile& in, ReadFaces faces, FileGeometry& g);
void read_off(InputFile& in, ReadFaces faces, FileGeometry& g);

// The polygons of `g` (read with ReadFaces::yes) as triangles, each fan-triangulated from its first
// corner: (c0, c(i), c(i+1)). What read_mesh returns.
std::vector<std::array<std::uint32_t, 3>> fan_triangles(const FileGeometry& g);

}  // namespace nmesh::io_detail
