// Tests of write_mesh / read_mesh / write_file_atomically: round trips in every format, the exact
// binary layout, colours, polygon triangulation, index errors, and the atomic-write guarantees.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/io.h"
#include "bunny_files.h"
#include "error_fixtures.h"
#include "io_fixtures.h"

#ifndef _WIN32
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

using nmesh::IndexedMesh;
using nmesh::Vec3;
using nmesh::test::refused_parameter;
using nmesh::test::refused_path;
using Triangle = std::array<std::uint32_t, 3>;

namespace {

namespace fs = std::filesystem;

const std::string kBunnyPly = nmesh::test::kBunnyPly;

struct TempDir : nmesh::test::TempDir {
    TempDir() : nmesh::test::TempDir("nmesh_mesh_io_") {}
};

std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

bool same_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same_bits);
}

// Finite floats of every magnitude, including subnormals and -0, and random triangles over them.
IndexedMesh random_mesh(std::size_t vertices, std::size_t triangles, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const auto value = [&] {
        for (;;) {
            const std::uint32_t bits = rng();
            float v = 0;
            std::memcpy(&v, &bits, sizeof v);
            if (std::isfinite(v)) return v;
        }
    };
    IndexedMesh mesh;
    mesh.positions.resize(vertices);
    for (Vec3& p : mesh.positions) p = {value(), value(), value()};
    if (vertices > 0) mesh.positions[0] = {-0.0f, 0.0f, std::numeric_limits<float>::denorm_min()};
    std::uniform_int_distribution<std::uint32_t> index(0, static_cast<std::uint32_t>(vertices) - 1);
    mesh.triangles.resize(triangles);
    for (Triangle& t : mesh.triangles) t = {index(rng), index(rng), index(rng)};
    return mesh;
}

// The IoError message thrown by read_mesh(path), checked to be one line starting with the path.
std::string read_error(const std::string& path) {
    return nmesh::test::io_error_of(path, [](const std::string& p) { nmesh::read_mesh(p); });
}

void check_read_error(const std::string& path, std::initializer_list<const char*> fragments) {
    const std::string message = read_error(path);
    for (const char* f : fragments) CHECK_MESSAGE(message.find(f) != std::string::npos, message);
}

template <class T>
void put(std::string& out, T v, bool big_endian) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    const std::uint16_t one = 1;
    char first = 0;
    std::memcpy(&first, &one, 1);
    if (big_endian == (first == 1)) std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

bool has_temporaries(const TempDir& dir) {
    const auto names = dir.names();
    return std::any_of(names.begin(), names.end(),
                       [](const std::string& n) { return n.find(".tmp-") != std::string::npos; });
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Round trips

TEST_CASE("write_mesh then read_mesh gives the same mesh bit for bit in every format") {
    const IndexedMesh mesh = random_mesh(700, 1300, 3);
    TempDir dir;
    struct Case {
        const char* name;
        bool ascii;
    };
    for (const Case c : {Case{"m.ply", false}, Case{"ascii.ply", true}, Case{"m.obj", false}, Case{"m.off", false},
                         Case{"UPPER.PLY", false}, Case{"upper.OBJ", false}}) {
        CAPTURE(c.name);
        nmesh::MeshWriteOptions options;
        options.ply_ascii = c.ascii;
        nmesh::write_mesh(dir.at(c.name), mesh, options);
        const IndexedMesh back = nmesh::read_mesh(dir.at(c.name));
        CHECK(same_points(back.positions, mesh.positions));
        CHECK(back.triangles == mesh.triangles);
        CHECK(same_points(nmesh::read_points(dir.at(c.name)).points, mesh.positions));
    }
    CHECK(nmesh::inspect_file(dir.at("ascii.ply")).encoding == "ascii");
    CHECK(nmesh::inspect_file(dir.at("m.ply")).encoding == "binary_little_endian");
    CHECK_FALSE(has_temporaries(dir));
}

TEST_CASE("an empty mesh round-trips in every format") {
    TempDir dir;
    for (const char* name : {"e.ply", "e.obj", "e.off"}) {
        CAPTURE(name);
        nmesh::write_mesh(dir.at(name), IndexedMesh{});
        const IndexedMesh back = nmesh::read_mesh(dir.at(name));
        CHECK(back.positions.empty());
        CHECK(back.triangles.empty());
    }
}

TEST_CASE("binary PLY: the exact header and record layout") {
    IndexedMesh mesh;
    mesh.positions = {{1.5f, -2, 0.25f}, {3, 4, 5}, {6, 7, 8}};
    mesh.triangles = {{0, 1, 2}, {2, 1, 0}};
    TempDir dir;
    nmesh::write_mesh(dir.at("m.ply"), mesh);
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
    std::string body;
    for (const Vec3& p : mesh.positions) {
        put(body, p.x, false);
        put(body, p.y, false);
        put(body, p.z, false);
    }
    for (const Triangle& t : mesh.triangles) {
        body += '\3';
        for (std::uint32_t v : t) put(body, static_cast<std::int32_t>(v), false);
    }
    CHECK(contents(dir.at("m.ply")) == header + body);
}

TEST_CASE("text formats: the exact layout") {
    IndexedMesh mesh;
    mesh.positions = {{1.5f, -2, 0.1f}, {3, 4, 5}, {6, 7, 8}};
    mesh.triangles = {{0, 1, 2}};
    TempDir dir;
    nmesh::write_mesh(dir.at("m.obj"), mesh);
    CHECK(contents(dir.at("m.obj")) == "# 3 vertices, 1 triangles\nv 1.5 -2 0.1\nv 3 4 5\nv 6 7 8\nf 1 2 3\n");
    nmesh::write_mesh(dir.at("m.off"), mesh);
    CHECK(contents(dir.at("m.off")) == "OFF\n3 1 0\n1.5 -2 0.1\n3 4 5\n6 7 8\n3 0 1 2\n");
}

TEST_CASE("vertex colours are written to PLY (both encodings) and OFF, and do not disturb reading") {
    IndexedMesh mesh;
    mesh.positions = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
    mesh.triangles = {{0, 1, 2}};
    nmesh::MeshWriteOptions options;
    options.colors = {{{255, 0, 10}}, {{0, 128, 20}}, {{1, 2, 3}}};
    TempDir dir;

    nmesh::write_mesh(dir.at("c.ply"), mesh, options);
    const std::string binary = contents(dir.at("c.ply"));
    const std::string color_props = "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    REQUIRE(binary.find(color_props) != std::string::npos);
    const std::size_t body = binary.find("end_header\n") + 11;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t c = 0; c < 3; ++c)
            CHECK(static_cast<std::uint8_t>(binary[body + 15 * i + 12 + c]) == options.colors[i][c]);
    CHECK(binary.size() == body + 3 * 15 + 13);

    options.ply_ascii = true;
    nmesh::write_mesh(dir.at("a.ply"), mesh, options);
    const std::string ascii = contents(dir.at("a.ply"));
    CHECK(ascii.find(color_props) != std::string::npos);
    CHECK(ascii.find("end_header\n1 2 3 255 0 10\n4 5 6 0 128 20\n7 8 9 1 2 3\n3 0 1 2\n") != std::string::npos);

    nmesh::write_mesh(dir.at("c.off"), mesh, options);
    CHECK(contents(dir.at("c.off")) ==
          "COFF\n3 1 0\n1 2 3 255 0 10 255\n4 5 6 0 128 20 255\n7 8 9 1 2 3 255\n3 0 1 2\n");

    nmesh::write_mesh(dir.at("c.obj"), mesh, options);  // no colours in OBJ
    CHECK(contents(dir.at("c.obj")) == "# 3 vertices, 1 triangles\nv 1 2 3\nv 4 5 6\nv 7 8 9\nf 1 2 3\n");

    for (const char* name : {"c.ply", "a.ply", "c.off"}) {
        CAPTURE(name);
        const IndexedMesh back = nmesh::read_mesh(dir.at(name));
        CHECK(same_points(back.positions, mesh.positions));
        CHECK(back.triangles == mesh.triangles);
    }
}

// ---------------------------------------------------------------------------------------------
// Reading meshes

TEST_CASE("read_mesh reads an ASCII PLY shaped like the Stanford meshes: bunny.ply's points and the faces") {
    TempDir dir;
    nmesh::test::write_bunny_ascii_mesh(dir.at("bunny_mesh.ply"));
    const IndexedMesh mesh = nmesh::read_mesh(dir.at("bunny_mesh.ply"));
    CHECK(same_points(mesh.positions, nmesh::read_points(kBunnyPly).points));
    CHECK(mesh.triangles == nmesh::test::bunny_strip_faces());
}

TEST_CASE("read_mesh of a point file gives its points and no triangles") {
    TempDir dir;
    nmesh::test::write_bunny_xyz(dir.at("bunny.xyz"));
    const IndexedMesh mesh = nmesh::read_mesh(dir.at("bunny.xyz"));
    CHECK(same_points(mesh.positions, nmesh::read_points(kBunnyPly).points));
    CHECK(mesh.triangles.empty());
}

TEST_CASE("PLY polygons are fan-triangulated; face element first, vertex_index, other index types") {
    // Why: a quad and a pentagon, and the face element declared before the vertex element.
    const std::vector<Triangle> expected = {{0, 1, 2}, {0, 2, 3}, {4, 0, 3}, {4, 3, 2}, {4, 2, 1}};
    const std::string header_faces_first =
        "element face 2\nproperty uchar flags\nproperty list ushort uint vertex_index\n"
        "element vertex 5\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1}};
    TempDir dir;
    {
        std::string ply = "ply\nformat ascii 1.0\n" + header_faces_first + "7 4 0 1 2 3\n9 5 4 0 3 2 1\n";
        for (const Vec3& p : positions)
            ply += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
        const IndexedMesh mesh = nmesh::read_mesh(dir.file("a.ply", ply));
        CHECK(mesh.triangles == expected);
        CHECK(same_points(mesh.positions, positions));
    }
    for (const bool big : {false, true}) {
        CAPTURE(big);
        std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                          " 1.0\n" + header_faces_first;
        const std::vector<std::vector<std::uint32_t>> faces = {{0, 1, 2, 3}, {4, 0, 3, 2, 1}};
        for (const auto& f : faces) {
            put(ply, std::uint8_t{7}, big);
            put(ply, static_cast<std::uint16_t>(f.size()), big);
            for (std::uint32_t v : f) put(ply, v, big);
        }
        for (const Vec3& p : positions) {
            put(ply, p.x, big);
            put(ply, p.y, big);
            put(ply, p.z, big);
        }
        const IndexedMesh mesh = nmesh::read_mesh(dir.file("b.ply", ply));
        CHECK(mesh.triangles == expected);
        CHECK(same_points(mesh.positions, positions));
    }
}

TEST_CASE("OBJ faces: v, v/vt, v/vt/vn, v//vn corners, negative indices, polygons") {
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvn 0 0 1\n"
        "f 1 2 3\n"
        "f 1/1 3/1 4/1\n"
        "f 1/1/1 2/1/1 4/1/1\n"
        "f 2//1 3//1 4//1\n"
        "f -4 -3 -2 -1\n"  // relative to the 4 vertices above: 1 2 3 4
        "v 5 5 5\n"
        "f -1 1 2\n";  // -1 is now vertex 5
    TempDir dir;
    const IndexedMesh mesh = nmesh::read_mesh(dir.file("m.obj", obj));
    CHECK(mesh.positions.size() == 5);
    CHECK(mesh.triangles ==
          std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}, {0, 1, 2}, {0, 2, 3}, {4, 0, 1}});
}

TEST_CASE("OFF faces: polygons and trailing face colours") {
    TempDir dir;
    const std::string off = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n4 0 1 2 3 255 0 0\n3 4 0 1\n";
    const IndexedMesh mesh = nmesh::read_mesh(dir.file("m.off", off));
    CHECK(mesh.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {4, 0, 1}});
}

TEST_CASE("read_mesh errors: indices out of range, short faces, missing face lists, non-finite vertices") {
    TempDir dir;
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\n";
    const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
    const std::string faces = "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    check_read_error(dir.file("hi.ply", head + faces + verts + "3 0 1 2\n3 0 1 3\n"),
                     {"line 14", "face 1: vertex index 3 is out of range (the file has 3 vertices)"});
    check_read_error(dir.file("neg.ply", head + faces + verts + "3 0 1 2\n3 0 -1 2\n"),
                     {"line 14", "vertex index -1 is out of range"});
    check_read_error(dir.file("two.ply", head + faces + verts + "2 0 1\n3 0 1 2\n"),
                     {"line 13", "face 0 has 2 corners; a face needs at least 3"});
    check_read_error(dir.file("word.ply", head + faces + verts + "3 0 1 2\n3 0 x 2\n"),
                     {"line 14", "vertex index 'x' is not an integer"});
    check_read_error(dir.file("nolist.ply", head + "element face 1\nproperty list uchar int corners\nend_header\n" +
                                                verts + "3 0 1 2\n"),
                     {"element 'face' has no 'vertex_indices' list property"});
    check_read_error(dir.file("float.ply", head +
                                               "element face 1\nproperty list uchar float vertex_indices\n"
                                               "end_header\n" +
                                               verts + "3 0 1 2\n"),
                     {"'vertex_indices' of element 'face' does not have an integer type"});
    check_read_error(dir.file("nan.ply", head + "end_header\n0 0 0\nnan 0 0\n0 1 0\n"),
                     {"vertex 1 has a non-finite coordinate"});
    // The same index error in a binary file names the byte offset of the face's list.
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const std::size_t face_offset = binary.size() + 36;
    for (int i = 0; i < 9; ++i) put(binary, 0.0f, false);
    binary += '\3';
    for (std::int32_t v : {0, 7, 1}) put(binary, v, false);
    check_read_error(dir.file("hi_bin.ply", binary),
                     {("byte offset " + std::to_string(face_offset)).c_str(), "vertex index 7 is out of range"});

    check_read_error(dir.file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
                     {"line 4", "vertex index 0 (OBJ indices start at 1)"});
    check_read_error(dir.file("hi.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n"),
                     {"line 3", "vertex index 3 is out of range (2 vertices are defined above this line)"});
    check_read_error(dir.file("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n"),
                     {"line 4", "vertex index -4 is out of range"});
    check_read_error(dir.file("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999/1\n"),
                     {"line 4", "vertex index 99999999999999999999 is out of range (3 vertices"});
    check_read_error(dir.file("hugeneg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -99999999999999999999\n"),
                     {"line 4", "vertex index -99999999999999999999 is out of range"});
    check_read_error(dir.file("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), {"line 3", "at least 3 corners, found 2"});
    check_read_error(dir.file("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 b 2\n"),
                     {"line 4", "face corner 'b' does not start with a vertex index"});
    check_read_error(dir.file("hi.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                     {"line 6", "vertex index 3 is out of range"});
    check_read_error(dir.file("huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 18446744073709551616\n"),
                     {"line 6", "vertex index '18446744073709551616' is out of range"});
    check_read_error(dir.file("two.off", "OFF\n3 1 0\n0.0 0 0\n1.0 0 0\n0.0 1 0\n2 0 1\n"),
                     {"line 6", "corner count '2' is not an integer >= 3"});
}

// ---------------------------------------------------------------------------------------------
// Writing: refusals and the atomic guarantee

TEST_CASE("write_mesh refuses an unknown extension or a missing directory, creating nothing") {
    const IndexedMesh mesh = random_mesh(4, 2, 1);
    TempDir dir;
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(dir.at("m.stl"), mesh), doctest::Contains("unknown mesh format '.stl'"),
                         nmesh::IoError);
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(dir.at("mesh"), mesh), doctest::Contains("(no extension)"), nmesh::IoError);
    const std::string missing = dir.at("no/such/dir/m.ply");
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(missing, mesh),
                         doctest::Contains((missing + ": cannot write: directory").c_str()), nmesh::IoError);
    CHECK(dir.names().empty());
    fs::create_directories(dir.path / "sub");
    std::ofstream(dir.at("sub/file")) << "x";
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(dir.at("sub/file/m.ply"), mesh), doctest::Contains("is not a directory"),
                         nmesh::IoError);
    CHECK(dir.names() == std::vector<std::string>{"sub"});
}

TEST_CASE("a refused write names its file (IoError::path()) and a refused option its name (ParameterError::parameter())") {
    const IndexedMesh mesh = random_mesh(4, 2, 1);
    TempDir dir;
    const std::string stl = dir.at("m.stl"), missing = dir.at("no/such/dir/m.ply");
    CHECK(refused_path([&] { nmesh::write_mesh(stl, mesh); }) == stl);
    CHECK(refused_path([&] { nmesh::write_mesh(missing, mesh); }) == missing);
    CHECK(refused_path([&] { nmesh::check_mesh_output(missing); }) == missing);
    CHECK(refused_path([&] { nmesh::check_output_location(""); }).empty());
    CHECK(std::string(nmesh::IoError("", "no name").what()) == "(empty path): no name");
    CHECK(std::string(nmesh::IoError("a.ply", "truncated").what()) == "a.ply: truncated");
    nmesh::MeshWriteOptions options;
    options.colors.resize(3);
    CHECK(refused_parameter([&] { nmesh::write_mesh(dir.at("m.ply"), mesh, options); }) == "colors");
    CHECK(dir.names().empty());
}

TEST_CASE("check_mesh_output and check_output_location refuse what writing would, creating nothing") {
    TempDir dir;
    const std::string missing = dir.at("no/such/dir/m.ply");
    CHECK_THROWS_WITH_AS(nmesh::check_mesh_output(dir.at("m.stl")), doctest::Contains("unknown mesh format '.stl'"),
                         nmesh::IoError);
    CHECK_NOTHROW(nmesh::check_output_location(dir.at("m.stl")));  // any name will do for a plain file
    CHECK_THROWS_WITH_AS(nmesh::check_mesh_output(missing),
                         doctest::Contains((missing + ": cannot write: directory").c_str()), nmesh::IoError);
    CHECK_THROWS_WITH_AS(nmesh::check_output_location(dir.at("no/stats.json")), doctest::Contains("does not exist"),
                         nmesh::IoError);
    CHECK_THROWS_WITH_AS(nmesh::check_output_location(""), doctest::Contains("without a name"), nmesh::IoError);
    std::ofstream(dir.at("file")) << "x";
    CHECK_THROWS_WITH_AS(nmesh::check_output_location(dir.at("file/stats.json")),
                         doctest::Contains("is not a directory"), nmesh::IoError);
    CHECK_NOTHROW(nmesh::check_mesh_output(dir.at("m.PLY")));
    CHECK_NOTHROW(nmesh::check_mesh_output(dir.at("file.obj")));
    CHECK(dir.names() == std::vector<std::string>{"file"});
}

TEST_CASE(
    "write_mesh refuses meshes no reader could take back (InputError for the mesh, ParameterError for the options; "
    "nothing written)") {
    TempDir dir;
    const std::string path = dir.at("m.ply");
    IndexedMesh mesh = random_mesh(4, 2, 2);
    nmesh::MeshWriteOptions options;
    options.colors.resize(3);
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(path, mesh, options),
                         doctest::Contains("options.colors has 3 entries for 4"), nmesh::ParameterError);
    IndexedMesh bad_index = mesh;
    bad_index.triangles[1] = {0, 4, 1};
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(path, bad_index), doctest::Contains("mesh.triangles[1] uses vertex 4 of 4"),
                         nmesh::InputError);
    IndexedMesh bad_point = mesh;
    bad_point.positions[2].y = std::numeric_limits<float>::infinity();
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(path, bad_point), doctest::Contains("mesh.positions[2] is not finite"),
                         nmesh::InputError);
    CHECK(dir.names().empty());
}

TEST_CASE("write_file_atomically: the body writes a temporary beside the target, renamed at the end") {
    TempDir dir;
    const std::string target = dir.at("stats.json");
    std::vector<std::string> seen_during_body;
    nmesh::write_file_atomically(target, [&](std::ostream& os) {
        os << "{\"a\": 1}\n";
        seen_during_body = dir.names();
    });
    REQUIRE(seen_during_body.size() == 1);
    CHECK(seen_during_body[0].rfind("stats.json.tmp-", 0) == 0);
    CHECK(dir.names() == std::vector<std::string>{"stats.json"});
    CHECK(contents(target) == "{\"a\": 1}\n");

    // Replacing an existing file.
    nmesh::write_file_atomically(target, [](std::ostream& os) { os << "second"; });
    CHECK(contents(target) == "second");
    CHECK(dir.names() == std::vector<std::string>{"stats.json"});

    // A path without a directory part is written in the current directory.
    {
        struct CwdGuard {
            fs::path saved = fs::current_path();
            ~CwdGuard() { fs::current_path(saved); }
        } guard;
        fs::current_path(dir.path);
        nmesh::write_file_atomically("plain.txt", [](std::ostream& os) { os << "x"; });
    }
    CHECK(contents(dir.at("plain.txt")) == "x");
}

TEST_CASE("write_file_atomically: on failure the target is untouched and no temporary is left") {
    TempDir dir;
    const std::string target = dir.at("m.ply");
    nmesh::write_file_atomically(target, [](std::ostream& os) { os << "old content"; });

    SUBCASE("the body throws: its exception comes through") {
        struct Boom : std::runtime_error {
            using std::runtime_error::runtime_error;
        };
        CHECK_THROWS_AS(nmesh::write_file_atomically(target,
                                                     [](std::ostream& os) {
                                                         os << "partial";
                                                         throw Boom("boom");
                                                     }),
                        Boom);
    }
    SUBCASE("the stream fails") {
        CHECK_THROWS_WITH_AS(nmesh::write_file_atomically(target,
                                                          [](std::ostream& os) {
                                                              os << "partial";
                                                              os.setstate(std::ios::badbit);
                                                          }),
                             doctest::Contains((target + ": write failed").c_str()), nmesh::IoError);
    }
    SUBCASE("write_mesh's preconditions fail") {
        IndexedMesh mesh = random_mesh(3, 1, 4);
        mesh.triangles[0][2] = 9;
        CHECK_THROWS_AS(nmesh::write_mesh(target, mesh), nmesh::InputError);
    }
    CHECK(contents(target) == "old content");
    CHECK(dir.names() == std::vector<std::string>{"m.ply"});
}

TEST_CASE("write_file_atomically: a target that is a directory is refused before anything is written") {
    TempDir dir;
    fs::create_directories(dir.path / "out.ply" / "inside");
    CHECK_THROWS_WITH_AS(nmesh::write_mesh(dir.at("out.ply"), random_mesh(3, 1, 5)),
                         doctest::Contains((dir.at("out.ply") + ": cannot write: is a directory").c_str()),
                         nmesh::IoError);
    CHECK_THROWS_WITH_AS(nmesh::check_mesh_output(dir.at("out.ply")),
                         doctest::Contains((dir.at("out.ply") + ": cannot write: is a directory").c_str()),
                         nmesh::IoError);
    CHECK(dir.names() == std::vector<std::string>{"out.ply"});
    CHECK(fs::is_directory(dir.path / "out.ply" / "inside"));
}

#ifndef _WIN32
TEST_CASE("write_file_atomically: a pipe or a device is written in place, not replaced by a file") {
    // A temporary renamed over /dev/null would turn it into a regular file for the whole system;
    // a FIFO in a scratch directory shows the same without that risk.
    TempDir dir;
    const std::string pipe = dir.at("pipe");
    REQUIRE(::mkfifo(pipe.c_str(), 0600) == 0);
    // Held open for reading and writing here, so that opening it to write does not block and
    // what is written stays in the pipe's buffer until read back.
    const int fd = ::open(pipe.c_str(), O_RDWR | O_NONBLOCK);
    REQUIRE(fd >= 0);
    CHECK_NOTHROW(nmesh::check_output_location(pipe));
    nmesh::write_file_atomically(pipe, [](std::ostream& os) { os << "{\"a\": 1}\n"; });
    char buf[64] = {};
    const ssize_t got = ::read(fd, buf, sizeof buf - 1);
    ::close(fd);
    CHECK(std::string(buf, got > 0 ? std::size_t(got) : 0) == "{\"a\": 1}\n");
    CHECK(fs::is_fifo(fs::status(pipe)));
    CHECK(dir.names() == std::vector<std::string>{"pipe"});  // no temporary left beside it
}
#endif
