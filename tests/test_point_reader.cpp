// Tests of read_points / inspect_file / read_geometry: the real scans, hand-made files in every
// PLY encoding and numeric type, the text formats, and every error the readers report.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/io.h"
#include "bunny_files.h"
#include "io_fixtures.h"

using nmesh::Vec3;

namespace {

namespace fs = std::filesystem;

using nmesh::test::kBunnyPoints;
const std::string kBunnyPly = nmesh::test::kBunnyPly;

struct TempDir : nmesh::test::TempDir {
    TempDir() : nmesh::test::TempDir("nmesh_point_reader_") {}
};

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

bool same_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same_bits);
}

// Finite floats of every magnitude (random bit patterns): exercises exponents and subnormals.
std::vector<Vec3> random_points(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    const auto value = [&] {
        for (;;) {
            const std::uint32_t bits = rng();
            float v = 0;
            std::memcpy(&v, &bits, sizeof v);
            if (std::isfinite(v)) return v;
        }
    };
    std::vector<Vec3> points(n);
    for (Vec3& p : points) p = {value(), value(), value()};
    return points;
}

// ---- A small independent PLY writer, so the reader is checked against files built here.

struct PlyProp {
    std::string type, name;
    std::string count_type;  // non-empty: a list property with this count type
};
struct PlyElem {
    std::string name;
    std::vector<PlyProp> props;
    // One row per record: scalars in order; a list as its count followed by its items.
    std::vector<std::vector<double>> rows;
};

bool host_little_endian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

void append_value(std::string& out, const std::string& encoding, const std::string& type, double v) {
    if (encoding == "ascii") {
        char text[64];
        if (type == "float" || type == "float32")
            std::snprintf(text, sizeof text, "%.9g", v);
        else if (type == "double" || type == "float64")
            std::snprintf(text, sizeof text, "%.17g", v);
        else
            std::snprintf(text, sizeof text, "%lld", static_cast<long long>(v));
        if (!out.empty() && out.back() != '\n') out += ' ';
        out += text;
        return;
    }
    unsigned char bytes[8];
    std::size_t n = 0;
    const auto put = [&](auto x) {
        n = sizeof x;
        std::memcpy(bytes, &x, n);
    };
    if (type == "char" || type == "int8")
        put(static_cast<std::int8_t>(v));
    else if (type == "uchar" || type == "uint8")
        put(static_cast<std::uint8_t>(v));
    else if (type == "short" || type == "int16")
        put(static_cast<std::int16_t>(v));
    else if (type == "ushort" || type == "uint16")
        put(static_cast<std::uint16_t>(v));
    else if (type == "int" || type == "int32")
        put(static_cast<std::int32_t>(v));
    else if (type == "uint" || type == "uint32")
        put(static_cast<std::uint32_t>(v));
    else if (type == "float" || type == "float32")
        put(static_cast<float>(v));
    else if (type == "double" || type == "float64")
        put(v);
    else
        FAIL("test writer: unknown type " << type);
    if ((encoding == "binary_big_endian") == host_little_endian()) std::reverse(bytes, bytes + n);
    out.append(reinterpret_cast<const char*>(bytes), n);
}

std::string make_ply(const std::string& encoding, const std::vector<PlyElem>& elems,
                     const std::string& extra_header = "") {
    std::string s = "ply\nformat " + encoding + " 1.0\n" + extra_header;
    for (const PlyElem& e : elems) {
        s += "element " + e.name + " " + std::to_string(e.rows.size()) + "\n";
        for (const PlyProp& p : e.props)
            s += p.count_type.empty() ? "property " + p.type + " " + p.name + "\n"
                                      : "property list " + p.count_type + " " + p.type + " " + p.name + "\n";
    }
    s += "end_header\n";
    for (const PlyElem& e : elems) {
        for (const auto& row : e.rows) {
            std::string record;
            std::size_t i = 0;
            for (const PlyProp& p : e.props) {
                if (p.count_type.empty()) {
                    append_value(record, encoding, p.type, row.at(i++));
                    continue;
                }
                const auto n = static_cast<long long>(row.at(i++));  // may be negative on purpose
                append_value(record, encoding, p.count_type, static_cast<double>(n));
                for (long long k = 0; k < n; ++k) append_value(record, encoding, p.type, row.at(i++));
            }
            s += record;
            if (encoding == "ascii") s += "\n";
        }
    }
    return s;
}

// A vertex-only PLY with x, y, z of the given type.
std::string xyz_ply(const std::string& encoding, const std::string& type, const std::vector<Vec3>& points) {
    PlyElem v{"vertex", {{type, "x", ""}, {type, "y", ""}, {type, "z", ""}}, {}};
    for (const Vec3& p : points) v.rows.push_back({p.x, p.y, p.z});
    return make_ply(encoding, {v});
}

const char* const kEncodings[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// The IoError message thrown by read_points(path), checked to be one line starting with the path.
std::string error_of(const std::string& path) {
    return nmesh::test::io_error_of(path, [](const std::string& p) { nmesh::read_points(p); });
}

// Checks that reading `path` fails with a message containing every fragment.
void check_error(const std::string& path, std::initializer_list<const char*> fragments) {
    const std::string message = error_of(path);
    for (const char* f : fragments) CHECK_MESSAGE(message.find(f) != std::string::npos, message);
}

std::vector<Vec3> bunny_points() {
    static const std::vector<Vec3> points = nmesh::read_points(kBunnyPly).points;
    return points;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Real scans

TEST_CASE("read_points reads bunny.ply: 35,947 points inside the documented bounding box") {
    nmesh::PointReadReport report;
    const nmesh::PointCloud cloud = nmesh::read_points(kBunnyPly, &report);
    CHECK(cloud.size() == kBunnyPoints);
    CHECK(report.format == "ply binary_little_endian");
    CHECK(report.points_read == kBunnyPoints);
    CHECK(report.non_finite_dropped == 0);
    // The box printed in the data README (6 significant digits).
    const nmesh::BoundingBox box = cloud.bounds();
    CHECK(box.min.x == doctest::Approx(-0.0946899).epsilon(1e-5));
    CHECK(box.min.y == doctest::Approx(0.0329874).epsilon(1e-5));
    CHECK(box.min.z == doctest::Approx(-0.0618736).epsilon(1e-5));
    CHECK(box.max.x == doctest::Approx(0.0610091).epsilon(1e-5));
    CHECK(box.max.y == doctest::Approx(0.187321).epsilon(1e-5));
    CHECK(box.max.z == doctest::Approx(0.0587997).epsilon(1e-5));
    CHECK(box.diagonal() == doctest::Approx(0.250246050).epsilon(1e-8));
}

TEST_CASE("bunny.xyz (shortest float text) reads back bit for bit as bunny.ply") {
    TempDir dir;
    nmesh::test::write_bunny_xyz(dir.at("bunny.xyz"));
    nmesh::PointReadReport report;
    const nmesh::PointCloud text = nmesh::read_points(dir.at("bunny.xyz"), &report);
    CHECK(report.format == "xyz");
    CHECK(same_points(text.points, bunny_points()));
}

TEST_CASE("an ASCII PLY shaped like the Stanford meshes (extra properties, faces): vertex i is point i of bunny.ply") {
    TempDir dir;
    const std::string path = dir.at("bunny_mesh.ply");
    nmesh::test::write_bunny_ascii_mesh(path);
    const nmesh::PointCloud mesh_points = nmesh::read_points(path);
    CHECK(same_points(mesh_points.points, bunny_points()));

    const nmesh::FileInfo info = nmesh::inspect_file(path);
    const std::uint64_t faces = nmesh::test::bunny_strip_faces().size();
    CHECK(info.format == "ply");
    CHECK(info.encoding == "ascii");
    CHECK(info.file_size == fs::file_size(path));
    REQUIRE(info.elements.size() == 2);
    CHECK(info.elements[0].name == "vertex");
    CHECK(info.elements[0].count == kBunnyPoints);
    CHECK(info.elements[0].properties ==
          std::vector<std::string>{"float x", "float y", "float z", "float confidence", "float intensity"});
    CHECK(info.elements[1].name == "face");
    CHECK(info.elements[1].count == faces);
    CHECK(info.elements[1].properties == std::vector<std::string>{"list uchar int vertex_indices"});
    CHECK(info.points == kBunnyPoints);
    CHECK(info.faces == faces);
    // The strip's triangles meet only at corners: a chain of bow-ties, every edge on the boundary.
    REQUIRE(info.topology);
    CHECK(info.topology_error.empty());
    CHECK_FALSE(info.topology->manifold);
    CHECK(info.topology->genus == -1);
    CHECK(info.topology->components == 1);
    CHECK(info.topology->boundary_edges == 3 * faces);
    CHECK(info.topology->isolated_vertices == kBunnyPoints - (2 * faces + 1));
}

TEST_CASE("inspect_file summarises bunny.ply") {
    const nmesh::FileInfo info = nmesh::inspect_file(kBunnyPly);
    CHECK(info.format == "ply");
    CHECK(info.encoding == "binary_little_endian");
    CHECK(info.file_size == 431483);
    REQUIRE(info.elements.size() == 1);
    CHECK(info.elements[0].properties == std::vector<std::string>{"float x", "float y", "float z"});
    CHECK(info.points == kBunnyPoints);
    CHECK(info.non_finite == 0);
    CHECK(info.faces == 0);
    CHECK_FALSE(info.topology);
    CHECK(info.topology_error.empty());
    const nmesh::BoundingBox box = nmesh::bounding_box(bunny_points());
    CHECK(same_bits(info.bounds.min, box.min));
    CHECK(same_bits(info.bounds.max, box.max));
}

TEST_CASE("inspect_file: the topology of the faces, or why there is none") {
    TempDir dir;
    // A unit cube without its top, as five quads: a box open at the top (a disc).
    const std::string box =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const nmesh::FileInfo open_box = nmesh::inspect_file(dir.file("box.obj", box));
    CHECK(open_box.faces == 5);
    REQUIRE(open_box.topology);
    CHECK(open_box.topology->manifold);
    CHECK_FALSE(open_box.topology->closed);
    CHECK(open_box.topology->euler == 1);  // 8 - 12 + 5, the quads' diagonals left out
    CHECK(open_box.topology->genus == 0);
    CHECK(open_box.topology->boundary_loops == 1);
    CHECK(open_box.topology->boundary_edges == 4);
    CHECK(open_box.topology->boundary_length == 4.0);
    const nmesh::FileInfo closed_box = nmesh::inspect_file(dir.file("closed.obj", box + "f 5 6 7 8\n"));
    REQUIRE(closed_box.topology);
    CHECK(closed_box.topology->closed);
    CHECK(closed_box.topology->euler == 2);
    CHECK(closed_box.topology->boundary_loops == 0);

    // A face that refers to a vertex not defined: the rest is summarised, the topology is not.
    const std::string bad = dir.file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    const nmesh::FileInfo info = nmesh::inspect_file(bad);
    CHECK(info.points == 3);
    CHECK(info.faces == 1);
    CHECK_FALSE(info.topology);
    CHECK(info.topology_error.find("out of range") != std::string::npos);
    CHECK_THROWS_AS(nmesh::read_mesh(bad), nmesh::IoError);
    // Errors in the points are still errors.
    CHECK_THROWS_AS(nmesh::inspect_file(dir.file("word.obj", "v 0 0 zero\nf 1 1 1\n")), nmesh::IoError);
}

// ---------------------------------------------------------------------------------------------
// Hand-made PLY files

TEST_CASE("PLY: x, y, z of every numeric type and alias, in every encoding") {
    // Values every type holds exactly: small integers, and quarters for the float types.
    const std::vector<Vec3> signed_points = {{-100, 0, 100}, {-1, 2, -3}, {127, -128, 5}};
    const std::vector<Vec3> unsigned_points = {{0, 1, 2}, {255, 17, 9}, {100, 200, 3}};
    const std::vector<Vec3> real_points = {{-1.25f, 0.5f, 3.75f}, {1e-3f, -2e7f, 0.1f}, {0, -0.0f, 7}};
    struct Case {
        const char* type;
        const std::vector<Vec3>* points;
    };
    const Case cases[] = {
        {"char", &signed_points},     {"int8", &signed_points},     {"uchar", &unsigned_points},
        {"uint8", &unsigned_points},  {"short", &signed_points},    {"int16", &signed_points},
        {"ushort", &unsigned_points}, {"uint16", &unsigned_points}, {"int", &signed_points},
        {"int32", &signed_points},    {"uint", &unsigned_points},   {"uint32", &unsigned_points},
        {"float", &real_points},      {"float32", &real_points},    {"double", &real_points},
        {"float64", &real_points},
    };
    TempDir dir;
    for (const Case& c : cases) {
        for (const char* encoding : kEncodings) {
            CAPTURE(c.type);
            CAPTURE(encoding);
            const std::string path =
                dir.file(std::string(c.type) + "_" + encoding + ".ply", xyz_ply(encoding, c.type, *c.points));
            nmesh::PointReadReport report;
            CHECK(same_points(nmesh::read_points(path, &report).points, *c.points));
            CHECK(report.format == std::string("ply ") + encoding);
        }
    }
}

TEST_CASE("PLY: x, y, z of different types in one record") {
    TempDir dir;
    PlyElem v{
        "vertex", {{"uchar", "x", ""}, {"double", "y", ""}, {"short", "z", ""}}, {{200, 0.125, -300}, {1, -2.5, 7}}};
    const std::vector<Vec3> expected = {{200, 0.125f, -300}, {1, -2.5f, 7}};
    for (const char* encoding : kEncodings) {
        CAPTURE(encoding);
        CHECK(same_points(nmesh::read_points(dir.file(std::string(encoding) + ".ply", make_ply(encoding, {v}))).points,
                          expected));
    }
}

TEST_CASE("PLY: comments, other elements (also before vertex), lists and extra properties are skipped") {
    // A vertex element with a list before x and one after z, normals, colours; an element with a
    // list before it, faces and a custom element after it.
    const PlyElem camera{
        "camera", {{"float", "focal", ""}, {"float", "params", "uchar"}}, {{35, 2, 0.5, 0.25}, {50, 0}}};
    const PlyElem vertex{"vertex",
                         {{"int", "tags", "uchar"},
                          {"float", "nx", ""},
                          {"double", "x", ""},
                          {"float", "y", ""},
                          {"uchar", "red", ""},
                          {"float", "z", ""},
                          {"short", "more", "int"}},
                         {{2, 7, 8, 0.5, 1.5, 2.5, 255, 3.5, 0},
                          {0, -1, -4.25, 5, 0, 6, 1, 30000},
                          {1, 9, 0, 1e-3, 2e-3, 3e-3, 4, 3, 1, 2, 3}}};
    const PlyElem face{
        "face", {{"int", "vertex_indices", "uchar"}, {"int", "flags", ""}}, {{3, 0, 1, 2, 7}, {4, 0, 1, 2, 0, 9}}};
    const PlyElem custom{"custom", {{"ushort", "q", ""}}, {{65535}}};
    const std::vector<Vec3> expected = {{1.5f, 2.5f, 3.5f}, {-4.25f, 5, 6}, {1e-3f, 2e-3f, 4}};
    const std::string comments = "comment made by hand\nobj_info also ignored\ncomment element vertex 99\n";
    TempDir dir;
    for (const char* encoding : kEncodings) {
        CAPTURE(encoding);
        const std::string path =
            dir.file(std::string(encoding) + ".ply", make_ply(encoding, {camera, vertex, face, custom}, comments));
        CHECK(same_points(nmesh::read_points(path).points, expected));

        const nmesh::FileInfo info = nmesh::inspect_file(path);
        REQUIRE(info.elements.size() == 4);
        CHECK(info.elements[0].name == "camera");
        CHECK(info.elements[0].count == 2);
        CHECK(info.elements[1].properties[0] == "list uchar int tags");
        CHECK(info.elements[3].name == "custom");
        CHECK(info.faces == 2);
        CHECK(info.points == 3);
    }
}

TEST_CASE("binary PLY: bodies larger than the read buffer give the same points in both byte orders") {
    // 90,000 records of 15 bytes (float x, y, z, uchar r, g, b) span two 1 MiB buffers with a
    // record split across the buffer end; the float-xyz-only file takes the direct-read path.
    // (ASCII lines across buffer ends: the Stanford-shaped bunny_mesh.ply above, 2.5 MB.)
    const std::vector<Vec3> points = random_points(90000, 7);
    PlyElem colored{"vertex",
                    {{"float", "x", ""},
                     {"float", "y", ""},
                     {"float", "z", ""},
                     {"uchar", "red", ""},
                     {"uchar", "green", ""},
                     {"uchar", "blue", ""}},
                    {}};
    for (const Vec3& p : points) colored.rows.push_back({p.x, p.y, p.z, 1, 2, 3});
    TempDir dir;
    for (const char* encoding : {"binary_little_endian", "binary_big_endian"}) {
        CAPTURE(encoding);
        CHECK(same_points(
            nmesh::read_points(dir.file(std::string(encoding) + ".ply", make_ply(encoding, {colored}))).points,
            points));
        CHECK(same_points(
            nmesh::read_points(dir.file(std::string(encoding) + "_xyz.ply", xyz_ply(encoding, "float", points))).points,
            points));
    }
}

TEST_CASE("PLY: a header with CRLF line ends and an element of count 0") {
    TempDir dir;
    const std::string ply =
        "ply\r\nformat ascii 1.0\r\nelement empty 0\r\nproperty float w\r\nelement vertex 2\r\n"
        "property float x\r\nproperty float y\r\nproperty float z\r\nend_header\r\n1 2 3\r\n4 5 6\r\n";
    CHECK(same_points(nmesh::read_points(dir.file("crlf.ply", ply)).points, {{1, 2, 3}, {4, 5, 6}}));
}

TEST_CASE("non-finite coordinates are dropped and counted, in every format") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Vec3> with_bad = {{1, 2, 3}, {nan, 0, 0}, {4, 5, 6}, {0, inf, 0}, {0, 0, -inf}};
    const std::vector<Vec3> good = {{1, 2, 3}, {4, 5, 6}};
    TempDir dir;
    for (const char* encoding : kEncodings) {
        CAPTURE(encoding);
        nmesh::PointReadReport report;
        CHECK(same_points(
            nmesh::read_points(dir.file(std::string(encoding) + ".ply", xyz_ply(encoding, "float", with_bad)), &report)
                .points,
            good));
        CHECK(report.non_finite_dropped == 3);
        CHECK(report.points_read == 2);
    }
    // A double beyond the float range becomes infinite, so it is dropped too.
    nmesh::PointReadReport report;
    const std::string huge = dir.file(
        "huge.ply",
        make_ply(
            "binary_little_endian",
            {{"vertex", {{"double", "x", ""}, {"double", "y", ""}, {"double", "z", ""}}, {{1e300, 0, 0}, {1, 2, 3}}}}));
    CHECK(same_points(nmesh::read_points(huge, &report).points, {{1, 2, 3}}));
    CHECK(report.non_finite_dropped == 1);

    const std::string text = dir.file("bad.xyz", "1 2 3\nnan 0 0\n0 inf 0\n0 0 -Infinity\n1e39 0 0\n4 5 6\n");
    CHECK(same_points(nmesh::read_points(text, &report).points, good));
    CHECK(report.non_finite_dropped == 4);
    const nmesh::FileInfo info = nmesh::inspect_file(text);
    CHECK(info.points == 2);
    CHECK(info.non_finite == 4);
    CHECK(same_bits(info.bounds.min, {1, 2, 3}));
    CHECK(same_bits(info.bounds.max, {4, 5, 6}));

    const std::string obj = dir.file("bad.obj", "v 1 2 3\nv nan 1 1\nv 4 5 6\n");
    CHECK(same_points(nmesh::read_points(obj, &report).points, good));
    CHECK(report.non_finite_dropped == 1);
}

// ---------------------------------------------------------------------------------------------
// Text formats

TEST_CASE("XYZ text: separators, comments, blank lines, extra columns, CRLF, '+' signs, a BOM") {
    const std::string text =
        "\xEF\xBB\xBF# a comment line\n"
        "1 2 3\n"
        "\n"
        "   \t  \n"
        "4,5,6\n"
        "7\t8\t9 extra columns are ignored 1 2\r\n"
        "+10, -11 ,1.2e1   # trailing comment\n"
        "  -1.5e-3 .5 -0\n"
        "13 14 15";  // no final line break
    const std::vector<Vec3> expected = {{1, 2, 3},   {4, 5, 6}, {7, 8, 9}, {10, -11, 12}, {-1.5e-3f, 0.5f, -0.0f},
                                        {13, 14, 15}};
    TempDir dir;
    for (const char* name : {"a.xyz", "a.txt", "a.csv", "a.pts", "A.XYZ", "a.Txt"}) {
        CAPTURE(name);
        nmesh::PointReadReport report;
        CHECK(same_points(nmesh::read_points(dir.file(name, text), &report).points, expected));
        CHECK(report.format == "xyz");
    }
}

TEST_CASE("XYZ text: lines longer than the read buffer boundary and a file of many lines") {
    // Random shortest-text floats over ~2.5 MB, so lines straddle buffer refills.
    const std::vector<Vec3> points = random_points(60000, 11);
    std::string text;
    char line[128];
    for (const Vec3& p : points) {
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", double{p.x}, double{p.y}, double{p.z});
        text += line;
    }
    TempDir dir;
    CHECK(same_points(nmesh::read_points(dir.file("many.xyz", text)).points, points));
}

TEST_CASE("text numbers are correctly rounded to float: random decimals against strtof") {
    // Why: the text reader has its own fast path for common decimals; strtof (correctly rounded)
    // is the reference. Covers 1 to 20 digits, exponents beyond +-22, values exactly halfway
    // between two floats (ties to even), the float range ends, subnormals and overflow.
    std::vector<std::string> tokens = {
        "16777217", "16777219", "1.6777217e7", "-16777217", "3.4028235e38", "3.40282357e38", "3.4028236e38", "1e39",
        "1.17549435e-38", "1.1754942e-38", "1e-40", "1e-50", "0.000000", "-0", "123456789012345678901", "0.1",
        "9007199254740993", "9007199254740992e-22",
        // decimals whose nearest double lies exactly halfway
        // between two floats, though they do not
        "5.541686732613016e-05", "1.698617398738861e+00", "7.694852054119110e-01", "6.249837344512343e-03"};
    std::mt19937 rng(13);
    const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    while (tokens.size() < 60000) {
        std::string t = pick(0, 3) == 0 ? "-" : "";
        const int digits = pick(1, 20);
        const int point = pick(0, digits);
        for (int i = 0; i < digits; ++i) {
            if (i == point && pick(0, 1) == 0) t += '.';
            t += static_cast<char>('0' + pick(0, 9));
        }
        if (pick(0, 2) == 0) t += "e" + std::to_string(pick(-45, 40));
        tokens.push_back(t);
    }
    std::string text;
    for (std::size_t i = 0; i < tokens.size(); i += 3)
        text += tokens[i] + " " + tokens[i + 1] + "," + tokens[i + 2] + "\n";
    TempDir dir;
    // read_geometry keeps the infinite values that read_points would drop.
    const std::vector<Vec3> points =
        nmesh::read_geometry(dir.file("numbers.xyz", text), nmesh::ReadFaces::no).positions;
    REQUIRE(points.size() == tokens.size() / 3);
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        const float expected = std::strtof(tokens[i].c_str(), nullptr);
        const float got = points[i / 3][static_cast<int>(i % 3)];
        if (std::memcmp(&expected, &got, sizeof got) != 0 && mismatches++ < 5) {
            char values[64];
            std::snprintf(values, sizeof values, "%.9g, strtof gives %.9g", double{got}, double{expected});
            FAIL_CHECK(tokens[i] << " read as " << values);
        }
    }
    CHECK(mismatches == 0);
}

TEST_CASE("PTS: a first line holding one integer (the point count) is skipped; elsewhere it is an error") {
    TempDir dir;
    const std::string pts = "# scan\n2\n1 2 3 100 10 20 30\n4 5 6 100 10 20 30\n";
    CHECK(same_points(nmesh::read_points(dir.file("scan.pts", pts)).points, {{1, 2, 3}, {4, 5, 6}}));
    check_error(dir.file("scan.xyz", pts), {"line 2", "expected 3 numbers (x y z), found 1"});
    check_error(dir.file("later.pts", "2\n1 2 3\n7\n"), {"line 3", "found 1"});
}

TEST_CASE("OBJ: 'v' lines are the points; everything else is ignored") {
    TempDir dir;
    const std::string obj =
        "# comment\nmtllib x.mtl\no thing\nv 1 2 3\nvn 0 0 1\nvt 0.5 0.5\nv 4 5 6 1.0\n"
        "v 7 8 9 0.1 0.2 0.3\ng group\nusemtl m\ns off\nf 1 2 3\nf 1/1/1 2/1/1 3/1/1\nl 1 2\n";
    nmesh::PointReadReport report;
    CHECK(same_points(nmesh::read_points(dir.file("m.obj", obj), &report).points, {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}));
    CHECK(report.format == "obj");
    const nmesh::FileInfo info = nmesh::inspect_file(dir.file("m.obj", obj));
    CHECK(info.faces == 2);
    CHECK(info.encoding == "text");
}

TEST_CASE("OFF: the vertex lines are the points") {
    TempDir dir;
    const std::string off = "OFF\n# comment\n3 1 0\n1 2 3\n4 5 6\n7 8 9\n3 0 1 2\n";
    CHECK(same_points(nmesh::read_points(dir.file("m.off", off)).points, {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}));
    const std::string coff = "COFF 2 0 0\n1 2 3 255 0 0 255\n4 5 6 0 255 0 255\n";
    CHECK(same_points(nmesh::read_points(dir.file("c.off", coff)).points, {{1, 2, 3}, {4, 5, 6}}));
    CHECK(nmesh::inspect_file(dir.file("m.off", off)).faces == 1);
}

TEST_CASE("an unknown extension is sniffed: PLY and OFF content are read, anything else is refused") {
    TempDir dir;
    CHECK(same_points(
        nmesh::read_points(dir.file("cloud.dat", xyz_ply("binary_big_endian", "float", {{1, 2, 3}}))).points,
        {{1, 2, 3}}));
    CHECK(same_points(nmesh::read_points(dir.file("noext", "OFF\n1 0 0\n1 2 3\n")).points, {{1, 2, 3}}));
    check_error(dir.file("cloud.dat2", "1 2 3\n"), {"unknown file format", "'.dat2'"});
    check_error(dir.file("noext2", "1 2 3\n"), {"unknown file format", "no extension"});
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the path and the problem

TEST_CASE("error: missing file, directory, empty file") {
    TempDir dir;
    check_error((dir.path / "absent.ply").string(), {"no such file"});
    fs::create_directory(dir.path / "sub.ply");
    check_error((dir.path / "sub.ply").string(), {"is a directory"});
    check_error(dir.file("empty.xyz", ""), {"empty file"});
    check_error(dir.file("empty.ply", ""), {"empty file"});
}

TEST_CASE("error: PLY header problems") {
    TempDir dir;
    const std::string vertex3 = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    SUBCASE("header only") {
        check_error(dir.file("h.ply", "ply\nformat binary_little_endian 1.0\n" + vertex3 + "end_header\n"),
                    {"header only", "1 'vertex'"});
    }
    SUBCASE("missing end_header") {
        check_error(dir.file("h.ply", "ply\nformat ascii 1.0\n" + vertex3), {"missing end_header"});
    }
    SUBCASE("not a PLY file") { check_error(dir.file("h.ply", "plyx\n"), {"not a PLY file"}); }
    SUBCASE("unknown format") {
        check_error(dir.file("h.ply", "ply\nformat binary_middle_endian 1.0\n" + vertex3 + "end_header\n1 2 3\n"),
                    {"line 2", "unknown PLY format 'binary_middle_endian'"});
    }
    SUBCASE("unknown version") {
        check_error(dir.file("h.ply", "ply\nformat ascii 2.0\n" + vertex3 + "end_header\n1 2 3\n"),
                    {"line 2", "unsupported PLY version '2.0'"});
    }
    SUBCASE("no format line") {
        check_error(dir.file("h.ply", "ply\n" + vertex3 + "end_header\n1 2 3\n"), {"no 'format' line"});
    }
    SUBCASE("unknown property type") {
        check_error(dir.file("h.ply",
                             "ply\nformat ascii 1.0\nelement vertex 1\nproperty int64 x\n"
                             "property float y\nproperty float z\nend_header\n1 2 3\n"),
                    {"line 4", "unknown property type 'int64'"});
    }
    SUBCASE("unknown keyword") {
        check_error(dir.file("h.ply", "ply\nformat ascii 1.0\n" + vertex3 + "elephant\nend_header\n1 2 3\n"),
                    {"line 7", "unknown PLY header keyword 'elephant'"});
    }
    SUBCASE("property before any element") {
        check_error(dir.file("h.ply", "ply\nformat ascii 1.0\nproperty float x\n" + vertex3 + "end_header\n1 2 3\n"),
                    {"line 3", "property line before any element"});
    }
    SUBCASE("bad element count") {
        check_error(dir.file("h.ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"),
                    {"line 3", "bad element line"});
    }
    SUBCASE("a float list count type") {
        check_error(
            dir.file("h.ply", "ply\nformat ascii 1.0\n" + vertex3 +
                                  "element face 0\nproperty list float int vertex_indices\nend_header\n1 2 3\n"),
            {"line 8", "list count type 'float' is not an integer type"});
    }
    SUBCASE("no vertex element") {
        check_error(dir.file("h.ply", "ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n1\n"),
                    {"no 'vertex' element"});
    }
    SUBCASE("missing x, y or z") {
        check_error(dir.file("h.ply",
                             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\n"
                             "end_header\n1 2\n"),
                    {"element 'vertex' has no 'y' property"});
    }
    SUBCASE("x as a list") {
        check_error(dir.file("h.ply",
                             "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\n"
                             "property float y\nproperty float z\nend_header\n1 1 2 3\n"),
                    {"property 'x' of element 'vertex' is a list"});
    }
}

TEST_CASE("error: a header declaring billions of records in a tiny file is refused before allocating") {
    TempDir dir;
    const std::string props = "property float x\nproperty float y\nproperty float z\nend_header\n";
    check_error(
        dir.file("b.ply",
                 "ply\nformat binary_little_endian 1.0\nelement vertex 3000000000\n" + props + std::string(24, '\0')),
        {"truncated binary body", "3000000000 'vertex'", "needing at least 36000000000 bytes", "only 24 bytes"});
    check_error(dir.file("a.ply", "ply\nformat ascii 1.0\nelement vertex 3000000000\n" + props + "1 2 3\n"),
                {"3000000000 'vertex'", "needing at least"});
    // Counts whose byte total overflows 64 bits.
    check_error(
        dir.file("o.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n" + props + "x"),
        {"18446744073709551615 'vertex'", "needing at least"});
    // A list count far beyond the file.
    PlyElem v{
        "vertex", {{"float", "x", ""}, {"float", "y", ""}, {"float", "z", ""}, {"float", "l", "uint"}}, {{1, 2, 3, 0}}};
    std::string ply = make_ply("binary_little_endian", {v});
    const std::string huge_count = "\xff\xff\xff\x7f";
    ply.replace(ply.size() - 4, 4, huge_count);
    check_error(dir.file("l.ply", ply), {"truncated binary body", "'vertex' record 0"});
}

TEST_CASE("error: truncated binary body, and data after the last record") {
    TempDir dir;
    std::ifstream in(kBunnyPly, std::ios::binary);
    const std::string bunny((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bunny.size() == 431483);
    check_error(dir.file("cut.ply", bunny.substr(0, bunny.size() - 5)),
                {"byte offset", "truncated binary body", "35947 'vertex'"});
    check_error(dir.file("long.ply", bunny + "junk"), {"byte offset 431483", "4 bytes of data after the last record"});
    CHECK(nmesh::read_points(dir.file("newline.ply", bunny + "\n")).size() == kBunnyPoints);

    // Cut inside a list-bearing element: found while walking the records.
    const PlyElem vertex{
        "vertex", {{"float", "x", ""}, {"float", "y", ""}, {"float", "z", ""}}, {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}};
    const PlyElem face{"face", {{"int", "vertex_indices", "uchar"}}, {{3, 0, 1, 2}, {3, 0, 2, 1}}};
    const std::string mesh = make_ply("binary_big_endian", {vertex, face});
    check_error(dir.file("cutface.ply", mesh.substr(0, mesh.size() - 3)),
                {"byte offset", "truncated binary body", "'face' record 1 of 2"});
}

TEST_CASE("error: ASCII PLY with fewer or more lines than the header declares") {
    TempDir dir;
    const std::string header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
        "z\nend_header\n";
    check_error(dir.file("few.ply", header + "1.000 2.000 3.000\n4.000 5.000 6.000\n\n"),
                {"ends after 2 of 3 'vertex' records"});
    check_error(dir.file("many.ply", header + "1 2 3\n4 5 6\n7 8 9\n10 11 12\n"),
                {"line 11", "more data than the header declares (3 'vertex')"});
    check_error(dir.file("short.ply", header + "1 2 3\n4.0 5.0\n7 8 9\n"),
                {"line 9", "'vertex' record 1 has fewer values than its 3 properties"});
    check_error(dir.file("long.ply", header + "1 2 3\n4 5 6 6.5\n7 8 9\n"),
                {"line 9", "'vertex' record 1 has more values than its 3 properties"});
    check_error(dir.file("word.ply", header + "1 2 3\n4 abc 6\n7 8 9\n"), {"line 9", "'abc' is not a number"});
}

TEST_CASE("error: binary list count that is negative") {
    TempDir dir;
    const PlyElem v{
        "vertex", {{"float", "l", "int"}, {"float", "x", ""}, {"float", "y", ""}, {"float", "z", ""}}, {{-2, 1, 2, 3}}};
    check_error(dir.file("neg.ply", make_ply("binary_little_endian", {v})), {"byte offset", "negative list count -2"});
}

TEST_CASE("error: XYZ text problems name the line") {
    TempDir dir;
    check_error(dir.file("two.xyz", "1 2 3\n4 5 6\n7 8\n"), {"line 3", "expected 3 numbers (x y z), found 2"});
    check_error(dir.file("word.xyz", "# c\n1 2 3\n4 five 6\n"), {"line 3", "'five' is not a number"});
    check_error(dir.file("half.xyz", "1 2 3x\n"), {"line 1", "'3x' is not a number"});
    check_error(dir.file("csvheader.csv", "x,y,z\n1,2,3\n"), {"line 1", "'x' is not a number"});

    std::mt19937 rng(5);
    std::string garbage(4096, '\0');
    for (char& c : garbage) c = static_cast<char>(rng() & 0xff);
    garbage[0] = '\x01';  // so that the first token is not a number by chance
    check_error(dir.file("garbage.xyz", garbage), {"line 1", "binary data, not text"});
    check_error(dir.file("nolines.xyz", std::string((1u << 20) + 10, '7')), {"line 1", "longer than 1 MiB"});
}

TEST_CASE("error: OBJ and OFF problems name the line") {
    TempDir dir;
    check_error(dir.file("v.obj", "v 1 2 3\nv 1 2\n"), {"line 2", "a 'v' line needs 3 coordinates, found 2"});
    check_error(dir.file("w.obj", "v 1 2 3\nv 1 two 3\n"), {"line 2", "'two' is not a number"});
    check_error(dir.file("few.off", "OFF\n3 0 0\n1.0 2.0 3.0\n4.0 5.0 6.0\n"), {"ends after 2 of 3 vertex lines"});
    check_error(dir.file("many.off", "OFF\n1 0 0\n1 2 3\n4 5 6\n"), {"line 4", "more lines than the header declares"});
    check_error(dir.file("bin.off", "OFF BINARY\n"), {"line 1", "binary OFF is not supported"});
    check_error(dir.file("head.off", "OF\n1 0 0\n1 2 3\n"), {"line 1", "not an OFF file"});
    check_error(dir.file("count.off", "OFF\n1 x 0\n1 2 3\n"), {"line 2", "bad face count 'x'"});
    check_error(dir.file("huge.off", "OFF\n4000000000 0 0\n1 2 3\n"), {"4000000000 vertices", "needing at least"});
}
