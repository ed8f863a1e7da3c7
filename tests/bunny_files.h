// The bundled bunny (examples/data/bunny.ply) and files made from it for the tests of the readers
// and writers, so that the suite needs nothing outside the repository.
#pragma once

#include <array>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/vec3.h"

namespace nmesh::test {

constexpr std::size_t kBunnyPoints = 35947;  // examples/data/README.md
inline const std::string kBunnyPly = std::string(NMESH_SOURCE_DIR) + "/examples/data/bunny.ply";

// The bunny's points, read without the library's readers.
inline const std::vector<Vec3>& bunny_scan() {
    static const std::vector<Vec3> points = read_scan(kBunnyPly);
    return points;
}

// The shortest decimal text that reads back as the same float (std::to_chars).
inline std::string shortest_text(float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

// Writes the bunny as text, one "x y z" line per point in the shortest decimal form of each float.
inline void write_bunny_xyz(const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    for (const Vec3& p : bunny_scan())
        out << shortest_text(p.x) << ' ' << shortest_text(p.y) << ' ' << shortest_text(p.z) << '\n';
}

// Triangles over the bunny's point indices for the face element of write_bunny_ascii_mesh: a
// strip through consecutive points (whatever their positions; the readers do not look at them).
inline std::vector<std::array<std::uint32_t, 3>> bunny_strip_faces() {
    std::vector<std::array<std::uint32_t, 3>> faces;
    for (std::uint32_t i = 0; i + 2 < kBunnyPoints; i += 2) faces.push_back({i, i + 1, i + 2});
    return faces;
}

// Writes the bunny as an ASCII PLY shaped like the Stanford originals (bun_zipper.ply): vertex
// properties x y z confidence intensity, then "3 a b c" faces of bunny_strip_faces(); a file of
// about 2.5 MB, so that the reader's 1 MiB buffer ends inside lines.
inline void write_bunny_ascii_mesh(const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    const auto faces = bunny_strip_faces();
    out << "ply\nformat ascii 1.0\ncomment made from bunny.ply for the tests\nelement vertex " << kBunnyPoints
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float confidence\n"
           "property float intensity\nelement face "
        << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    std::size_t i = 0;
    for (const Vec3& p : bunny_scan()) {
        out << shortest_text(p.x) << ' ' << shortest_text(p.y) << ' ' << shortest_text(p.z) << ' ' << (i % 7) * 0.125
            << ' ' << (i % 5) * 0.25 << '\n';
        ++i;
    }
    for (const auto& f : faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
}

}  // namespace nmesh::test
