// Tests of the PNG encoder and the software renderer. The PNG files are decoded by a small
// independent inflate (stored and fixed-Huffman blocks) written here, with every chunk CRC and
// the zlib Adler-32 checked; the renders are checked against the camera's projection of known
// meshes: coverage, visibility, lighting direction, back faces, views, wireframe and value
// colouring.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "error_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/render/png_writer.h"
#include "nmesh/render.h"

using nmesh::Camera;
using nmesh::Image;
using nmesh::IndexedMesh;
using nmesh::RenderOptions;
using nmesh::Vec3;
using nmesh::View;
using nmesh::test::refused_parameter;
using Bytes = std::vector<std::uint8_t>;
using Rgb = std::array<std::uint8_t, 3>;

namespace {

// ---- a minimal PNG decoder, independent of the encoder ---------------------------------------

struct BitReader {
    const Bytes& data;
    std::size_t pos = 0;  // in bits
    std::uint32_t bit() {
        if (pos / 8 >= data.size()) throw std::runtime_error("inflate: out of data");
        const std::uint32_t b = (data[pos / 8] >> (pos % 8)) & 1u;
        ++pos;
        return b;
    }
    std::uint32_t bits(int n) {  // least significant bit first
        std::uint32_t v = 0;
        for (int i = 0; i < n; ++i) v |= bit() << i;
        return v;
    }
    std::uint32_t huffman(int n) {  // a code of n bits, most significant bit first
        std::uint32_t v = 0;
        for (int i = 0; i < n; ++i) v = (v << 1) | bit();
        return v;
    }
};

// How many blocks of each type (0 stored, 1 fixed) an inflate met, and which length and
// distance codes.
struct InflateStats {
    int stored = 0, fixed = 0;
    std::set<int> length_codes, distance_codes;
};

// Decodes a zlib stream made of stored and fixed-Huffman blocks; checks the header and Adler-32.
Bytes inflate(const Bytes& z, InflateStats* stats = nullptr) {
    static const int kLenBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                     31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int kLenExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                      2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const int kDistBase[30] = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                      33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                      1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const int kDistExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                       6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    REQUIRE(z.size() >= 6);
    REQUIRE((z[0] & 0x0F) == 8);             // deflate
    REQUIRE((z[0] * 256 + z[1]) % 31 == 0);  // header check
    REQUIRE((z[1] & 0x20) == 0);             // no preset dictionary
    const Bytes body(z.begin() + 2, z.end() - 4);
    BitReader in{body};
    Bytes out;
    bool last = false;
    while (!last) {
        last = in.bits(1) == 1;
        const std::uint32_t type = in.bits(2);
        if (type == 0) {
            if (stats) ++stats->stored;
            in.pos = (in.pos + 7) / 8 * 8;
            const std::uint32_t len = in.bits(16), nlen = in.bits(16);
            REQUIRE(len == (~nlen & 0xFFFFu));
            for (std::uint32_t i = 0; i < len; ++i) out.push_back(std::uint8_t(in.bits(8)));
            continue;
        }
        REQUIRE(type == 1);  // the encoder writes no dynamic-Huffman blocks
        if (stats) ++stats->fixed;
        for (;;) {
            std::uint32_t code = in.huffman(7);
            int sym;
            if (code <= 0x17) {
                sym = 256 + int(code);
            } else {
                code = (code << 1) | in.bit();
                if (code >= 0x30 && code <= 0xBF)
                    sym = int(code) - 0x30;
                else if (code >= 0xC0 && code <= 0xC7)
                    sym = 280 + int(code) - 0xC0;
                else
                    sym = 144 + int(((code << 1) | in.bit()) - 0x190);
            }
            if (sym < 256) {
                out.push_back(std::uint8_t(sym));
                continue;
            }
            if (sym == 256) break;
            REQUIRE(sym <= 285);
            const int len = kLenBase[sym - 257] + int(in.bits(kLenExtra[sym - 257]));
            const std::uint32_t dsym = in.huffman(5);
            REQUIRE(dsym < 30);
            if (stats) {
                stats->length_codes.insert(sym);
                stats->distance_codes.insert(int(dsym));
            }
            const std::size_t dist = std::size_t(kDistBase[dsym]) + in.bits(kDistExtra[dsym]);
            REQUIRE(dist <= out.size());
            REQUIRE(dist <= 32768);
            for (int i = 0; i < len; ++i) out.push_back(out[out.size() - dist]);
        }
    }
    REQUIRE((in.pos + 7) / 8 == body.size());  // nothing after the last block
    const std::uint32_t adler = std::uint32_t(z[z.size() - 4]) << 24 | std::uint32_t(z[z.size() - 3]) << 16 |
                                std::uint32_t(z[z.size() - 2]) << 8 | z[z.size() - 1];
    std::uint32_t a = 1, b = 0;  // Adler-32, the slow obvious way
    for (std::uint8_t v : out) {
        a = (a + v) % 65521;
        b = (b + a) % 65521;
    }
    CHECK(adler == (b << 16 | a));
    return out;
}

std::uint32_t be32(const Bytes& d, std::size_t at) {
    return std::uint32_t(d[at]) << 24 | std::uint32_t(d[at + 1]) << 16 | std::uint32_t(d[at + 2]) << 8 | d[at + 3];
}

// CRC-32 bit by bit, independent of the encoder's table.
std::uint32_t slow_crc32(const std::uint8_t* p, std::size_t n) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

struct Decoded {
    int width = 0, height = 0;
    Bytes rgb;
    InflateStats blocks;
    std::vector<std::string> chunks;
};

// Decodes an 8-bit RGB, non-interlaced PNG; checks the signature, every chunk's CRC and the
// chunk order, and undoes the five row filters.
Decoded decode_png(const Bytes& png) {
    const Bytes signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    REQUIRE(png.size() > signature.size());
    REQUIRE(std::equal(signature.begin(), signature.end(), png.begin()));
    Decoded d;
    Bytes idat;
    std::size_t at = 8;
    while (at < png.size()) {
        REQUIRE(at + 12 <= png.size());
        const std::uint32_t len = be32(png, at);
        REQUIRE(at + 12 + len <= png.size());
        const std::string type(png.begin() + long(at) + 4, png.begin() + long(at) + 8);
        CHECK(be32(png, at + 8 + len) == slow_crc32(png.data() + at + 4, len + 4));
        d.chunks.push_back(type);
        const Bytes data(png.begin() + long(at) + 8, png.begin() + long(at + 8 + len));
        if (type == "IHDR") {
            REQUIRE(len == 13);
            d.width = int(be32(data, 0));
            d.height = int(be32(data, 4));
            CHECK(data[8] == 8);   // bit depth
            CHECK(data[9] == 2);   // RGB
            CHECK(data[10] == 0);  // deflate
            CHECK(data[11] == 0);  // adaptive filtering
            CHECK(data[12] == 0);  // no interlace
        } else if (type == "IDAT") {
            idat.insert(idat.end(), data.begin(), data.end());
        }
        at += 12 + len;
    }
    REQUIRE(d.chunks.size() >= 3);
    CHECK(d.chunks.front() == "IHDR");
    CHECK(d.chunks.back() == "IEND");
    const Bytes raw = inflate(idat, &d.blocks);
    const std::size_t stride = 3 * std::size_t(d.width);
    REQUIRE(raw.size() == (stride + 1) * std::size_t(d.height));
    d.rgb.resize(stride * std::size_t(d.height));
    for (std::size_t y = 0; y < std::size_t(d.height); ++y) {
        const std::uint8_t filter = raw[y * (stride + 1)];
        REQUIRE(filter <= 4);
        const std::uint8_t* src = &raw[y * (stride + 1) + 1];
        std::uint8_t* row = &d.rgb[y * stride];
        const std::uint8_t* up = y > 0 ? row - stride : nullptr;
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= 3 ? row[i - 3] : 0, b = up ? up[i] : 0, c = (up && i >= 3) ? up[i - 3] : 0;
            int pred = 0;
            switch (filter) {
                case 1:
                    pred = a;
                    break;
                case 2:
                    pred = b;
                    break;
                case 3:
                    pred = (a + b) / 2;
                    break;
                case 4: {
                    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
                    pred = (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
                    break;
                }
                default:
                    break;
            }
            row[i] = std::uint8_t(src[i] + pred);
        }
    }
    return d;
}

Bytes bytes_of(const char* s) { return Bytes(s, s + std::strlen(s)); }

// ---- meshes --------------------------------------------------------------------------------------

// Turns each triangle of a mesh that is star-shaped around `center` to face away from it.
void orient_outward(IndexedMesh& m, const Vec3& center) {
    for (auto& t : m.triangles) {
        const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
        if (nmesh::dot(nmesh::cross(b - a, c - a), (a + b + c) / 3.0f - center) < 0.0f) std::swap(t[1], t[2]);
    }
}

// An axis-aligned box, 8 shared corners and 12 outward triangles: the simplest closed mesh whose
// projections are known rectangles.
IndexedMesh box(const Vec3& center, const Vec3& half) {
    IndexedMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({center.x + ((i & 1) ? half.x : -half.x), center.y + ((i & 2) ? half.y : -half.y),
                               center.z + ((i & 4) ? half.z : -half.z)});
    // Each face: the 4 corners whose bit `axis` is `side`, in cyclic order.
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int b1 = 1 << ((axis + 1) % 3), b2 = 1 << ((axis + 2) % 3), base = side << axis;
            const std::uint32_t q[4] = {std::uint32_t(base), std::uint32_t(base | b1), std::uint32_t(base | b1 | b2),
                                        std::uint32_t(base | b2)};
            m.triangles.push_back({q[0], q[1], q[2]});
            m.triangles.push_back({q[0], q[2], q[3]});
        }
    }
    orient_outward(m, center);
    return m;
}

IndexedMesh cube() { return box({0, 0, 0}, {1, 1, 1}); }

// A tetrahedron with no symmetry that maps a view onto another: every view looks different.
IndexedMesh tetrahedron() {
    IndexedMesh m;
    m.positions = {{0.9f, -0.3f, 0.2f}, {-0.6f, -0.5f, 0.7f}, {-0.2f, 0.8f, -0.1f}, {0.1f, -0.4f, -0.9f}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    const Vec3 c = (m.positions[0] + m.positions[1] + m.positions[2] + m.positions[3]) / 4.0f;
    orient_outward(m, c);
    return m;
}

// A unit sphere: a cube's faces cut into n x n grids, pushed onto the sphere; corners shared so
// that smooth normals are those of the sphere.
IndexedMesh sphere(int n) {
    IndexedMesh m;
    std::map<std::array<int, 3>, std::uint32_t> index;
    auto vertex = [&](std::array<int, 3> k) {
        const auto it = index.find(k);
        if (it != index.end()) return it->second;
        const std::uint32_t v = std::uint32_t(m.positions.size());
        m.positions.push_back(nmesh::normalized(Vec3{float(k[0]), float(k[1]), float(k[2])}));
        index.emplace(k, v);
        return v;
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    auto corner = [&](int a, int b) {
                        std::array<int, 3> k{};
                        k[axis] = side * n;
                        k[(axis + 1) % 3] = 2 * a - n;
                        k[(axis + 2) % 3] = 2 * b - n;
                        return vertex(k);
                    };
                    const std::uint32_t q0 = corner(i, j), q1 = corner(i + 1, j), q2 = corner(i + 1, j + 1),
                                        q3 = corner(i, j + 1);
                    m.triangles.push_back({q0, q1, q2});
                    m.triangles.push_back({q0, q2, q3});
                }
            }
        }
    }
    orient_outward(m, {0, 0, 0});
    return m;
}

// An octahedron: equator corners (+-r, 0, 0), (0, +-r, 0) and poles (0, 0, +-R), R >= r, outward,
// the faces of the far (-z) half listed first. From the front its outline is the square of
// equator edges, where each front face meets a back face at the same depth.
IndexedMesh octahedron(float r, float R) {
    IndexedMesh m;
    m.positions = {{r, 0, 0}, {0, r, 0}, {-r, 0, 0}, {0, -r, 0}, {0, 0, -R}, {0, 0, R}};
    for (const std::uint32_t pole : {4u, 5u})
        for (std::uint32_t k = 0; k < 4; ++k) m.triangles.push_back({k, (k + 1) % 4, pole});
    orient_outward(m, {0, 0, 0});
    return m;
}

// sphere(n) without its cap towards +z (the triangles whose centre has z > 0.7): an open surface
// whose inside shows through the hole from the front.
IndexedMesh open_sphere(int n) {
    IndexedMesh m = sphere(n);
    std::vector<std::array<std::uint32_t, 3>> kept;
    for (const auto& t : m.triangles)
        if ((m.positions[t[0]].z + m.positions[t[1]].z + m.positions[t[2]].z) / 3.0f <= 0.7f) kept.push_back(t);
    m.triangles = kept;
    return m;
}

IndexedMesh merged(const IndexedMesh& a, const IndexedMesh& b) {
    IndexedMesh m = a;
    const std::uint32_t offset = std::uint32_t(a.positions.size());
    m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
    for (auto t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return m;
}

RenderOptions small(int w = 200, int h = 200) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.supersample = 1;
    return o;
}

bool covered(const Image& img, int x, int y, const Rgb& background = {255, 255, 255}) {
    return img.pixel(x, y) != background;
}

std::size_t covered_count(const Image& img) {
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) n += covered(img, x, y);
    return n;
}

// The smallest pixel rectangle holding every covered pixel: {x0, y0, x1, y1}, inclusive.
std::array<int, 4> covered_box(const Image& img) {
    std::array<int, 4> b{img.width, img.height, -1, -1};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (covered(img, x, y)) b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
    return b;
}

double distance_to_segment(double px, double py, const Vec3& a, const Vec3& b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double t = std::clamp(((px - a.x) * dx + (py - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    return std::hypot(px - (a.x + t * dx), py - (a.y + t * dy));
}

// Whether a pixel is `color` scaled by one factor (shaded), to within rounding; the factor goes
// to `shade`.
bool has_hue(const Rgb& pixel, const Rgb& color, double* shade = nullptr) {
    const double k = double(pixel[0] + pixel[1] + pixel[2]) / double(color[0] + color[1] + color[2]);
    if (shade) *shade = k;
    for (int i = 0; i < 3; ++i)
        if (std::fabs(pixel[i] - k * color[i]) > 2.0) return false;
    return true;
}

void check_close(const Vec3& a, const Vec3& b) {
    CHECK(a.x == doctest::Approx(b.x).epsilon(1e-6));
    CHECK(a.y == doctest::Approx(b.y).epsilon(1e-6));
    CHECK(a.z == doctest::Approx(b.z).epsilon(1e-6));
}

}  // namespace

// ---- PNG ---------------------------------------------------------------------------------------

TEST_CASE("crc32 and adler32 give the reference values and chain across calls") {
    const Bytes digits = bytes_of("123456789");
    CHECK(nmesh::crc32(digits.data(), digits.size()) == 0xCBF43926u);
    CHECK(nmesh::crc32(digits.data() + 4, 5, nmesh::crc32(digits.data(), 4)) == 0xCBF43926u);
    CHECK(nmesh::crc32(nullptr, 0) == 0u);
    const Bytes wiki = bytes_of("Wikipedia");
    CHECK(nmesh::adler32(wiki.data(), wiki.size()) == 0x11E60398u);
    CHECK(nmesh::adler32(wiki.data() + 3, 6, nmesh::adler32(wiki.data(), 3)) == 0x11E60398u);
    CHECK(nmesh::adler32(nullptr, 0) == 1u);

    // Long inputs of large bytes: the deferred modulo must not overflow.
    Bytes big(200000);
    std::mt19937 rng(7);
    for (auto& b : big) b = std::uint8_t(rng() % 2 ? 255 : rng());
    std::uint32_t a = 1, s = 0;
    for (std::uint8_t v : big) {
        a = (a + v) % 65521;
        s = (s + a) % 65521;
    }
    CHECK(nmesh::adler32(big.data(), big.size()) == (s << 16 | a));
    CHECK(nmesh::crc32(big.data(), big.size()) == slow_crc32(big.data(), big.size()));
}

TEST_CASE("encode_png round-trips pixels exactly through an independent decoder") {
    std::mt19937 rng(42);
    struct Case {
        const char* name;
        int w, h;
        std::function<Rgb(int, int)> pixel;
    };
    const std::vector<Case> cases = {
        {"one pixel", 1, 1,
         [](int, int) {
             return Rgb{12, 200, 7};
         }},
        {"odd sizes, random", 7, 5,
         [&](int, int) {
             return Rgb{std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng())};
         }},
        {"gradients", 301, 173,
         [](int x, int y) {
             return Rgb{std::uint8_t(x), std::uint8_t(y * 3), std::uint8_t(x + y)};
         }},
        {"constant", 400, 300,
         [](int, int) {
             return Rgb{255, 255, 255};
         }},
        {"stripes and blocks", 257, 129,
         [](int x, int y) {
             return ((x / 8 + y / 5) % 3) ? Rgb{std::uint8_t(x % 7 * 30), 9, 200} : Rgb{0, 0, 0};
         }},
        {"one row", 600, 1,
         [](int x, int) {
             return Rgb{std::uint8_t(x * x), std::uint8_t(x / 3), 1};
         }},
        {"one column", 1, 600,
         [](int, int y) {
             return Rgb{std::uint8_t(y), std::uint8_t(y % 2 * 255), 3};
         }},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        Bytes rgb;
        for (int y = 0; y < c.h; ++y)
            for (int x = 0; x < c.w; ++x) {
                const Rgb p = c.pixel(x, y);
                rgb.insert(rgb.end(), p.begin(), p.end());
            }
        const Decoded d = decode_png(nmesh::encode_png(c.w, c.h, rgb));
        CHECK(d.width == c.w);
        CHECK(d.height == c.h);
        CHECK(d.rgb == rgb);
    }
}

TEST_CASE("encode_png compresses flat areas and falls back to stored blocks for noise") {
    // Noise: no match to find, so stored blocks, and the file stays within a small overhead.
    const int w = 300, h = 300;
    Bytes noise(3 * w * h);
    std::mt19937 rng(3);
    for (auto& b : noise) b = std::uint8_t(rng());
    const Bytes noisy = nmesh::encode_png(w, h, noise);
    const Decoded dn = decode_png(noisy);
    CHECK(dn.rgb == noise);
    CHECK(dn.blocks.stored > 0);
    const std::size_t raw = noise.size() + h;  // pixels plus one filter byte per row
    CHECK(noisy.size() <= raw + 5 * (raw / 65535 + 1) + 100);

    // A flat image: fixed-Huffman blocks and long matches, far below the raw size.
    const Bytes flat(3 * w * h, 200);
    const Bytes small_png = nmesh::encode_png(w, h, flat);
    const Decoded df = decode_png(small_png);
    CHECK(df.rgb == flat);
    CHECK(df.blocks.fixed > 0);
    CHECK(df.blocks.stored == 0);
    CHECK(small_png.size() < raw / 100);
}

TEST_CASE("zlib_compress uses every length and distance code correctly") {
    // Random bytes below 144 (8-bit literals under the fixed code, so the fixed block beats a
    // stored one) with planted copies: each length code's smallest length at each distance code's
    // smallest distance, and the extremes 258 and 32768. The bytes around each copy differ from
    // those around its source, so the match found is exactly the planted one.
    static const int kLengths[] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                   31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int kDistances[] = {1,    2,    3,    4,    5,    7,     9,     13,    17,   25,   33,
                                     49,   65,   97,   129,  193,  257,   385,   513,   769,  1025, 1537,
                                     2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577, 32768};
    std::mt19937 rng(11);
    const auto byte = [&] { return std::uint8_t(rng() % 144); };
    const auto byte_not = [&](std::uint8_t avoid) { return std::uint8_t((avoid + 1 + rng() % 143) % 144); };
    Bytes data(33000);
    for (auto& b : data) b = byte();
    for (int i = 0; i < 31; ++i) {
        const std::size_t d = std::size_t(kDistances[i]), len = std::size_t(kLengths[i % 29]);
        for (int k = 0; k < 5; ++k) data.push_back(byte());
        // The byte before the copy differs from the one before its source (for d > 1 they are
        // distinct positions), so the match cannot start earlier.
        const std::size_t from = data.size() + 1 - d;
        data.push_back(d > 1 ? byte_not(data[from - 1]) : byte());
        for (std::size_t k = 0; k < len; ++k) data.push_back(data[from + k]);
        data.push_back(byte_not(data[from + len]));  // nor extend past its end
    }
    InflateStats stats;
    CHECK(inflate(nmesh::zlib_compress(data), &stats) == data);
    CHECK(stats.fixed == 1);
    CHECK(stats.length_codes.size() == 29);
    CHECK(stats.distance_codes.size() == 30);
    CHECK(inflate(nmesh::zlib_compress({})).empty());
}

TEST_CASE("encode_png refuses sizes that do not match the pixels") {
    CHECK(refused_parameter([] { nmesh::encode_png(0, 1, {}); }) == "width");
    CHECK(refused_parameter([] { nmesh::encode_png(1, -1, {}); }) == "height");
    CHECK(refused_parameter([] { nmesh::encode_png(2, 2, Bytes(11)); }) == "rgb");
    CHECK(refused_parameter([] { nmesh::encode_png(2, 2, Bytes(13)); }) == "rgb");
    CHECK_NOTHROW(nmesh::encode_png(2, 2, Bytes(12)));
}

TEST_CASE("write_png writes the encoded bytes, and nothing when it fails") {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() /
        ("nmesh_render_" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    fs::create_directories(dir);
    const Bytes rgb = {1, 2, 3, 4, 5, 6};
    const std::string path = (dir / "a.png").string();
    nmesh::write_png(path, 2, 1, rgb);
    std::ifstream in(path, std::ios::binary);
    const Bytes written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(written == nmesh::encode_png(2, 1, rgb));
    CHECK(decode_png(written).rgb == rgb);

    CHECK_THROWS_AS(nmesh::write_png((dir / "missing" / "b.png").string(), 2, 1, rgb), nmesh::IoError);
    CHECK_THROWS_AS(nmesh::write_png((dir / "c.png").string(), 3, 1, rgb), nmesh::ParameterError);
    CHECK_FALSE(fs::exists(dir / "c.png"));
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);  // no temporaries
    fs::remove_all(dir);
}

// ---- the camera ----------------------------------------------------------------------------------

TEST_CASE("the named views point the camera as documented (y up, front from +z)") {
    const IndexedMesh m = cube();
    RenderOptions o = small();
    o.view = View::front();
    Camera c = nmesh::frame_camera(m, o);
    check_close(c.right, {1, 0, 0});
    check_close(c.up, {0, 1, 0});
    check_close(c.toward, {0, 0, 1});
    o.view = View::side();
    c = nmesh::frame_camera(m, o);
    check_close(c.right, {0, 0, -1});
    check_close(c.up, {0, 1, 0});
    check_close(c.toward, {1, 0, 0});
    o.view = View::top();
    c = nmesh::frame_camera(m, o);
    check_close(c.right, {1, 0, 0});
    check_close(c.up, {0, 0, -1});
    check_close(c.toward, {0, 1, 0});
    o.view = View::iso();
    c = nmesh::frame_camera(m, o);
    const float k = 1.0f / std::sqrt(3.0f);
    check_close(c.toward, {k, k, k});
    CHECK(c.up.y > 0.0f);
}

TEST_CASE("frame_camera fits the bounding sphere into the image with the margin") {
    const IndexedMesh m = box({10, -3, 5}, {1, 2, 2});  // bounding sphere radius 3
    RenderOptions o = small(400, 250);
    const Camera c = nmesh::frame_camera(m, o);
    check_close(c.center, {10, -3, 5});
    CHECK(c.scale == doctest::Approx((1 - 2 * nmesh::kRenderMargin) * 250 / 6.0));
    const Vec3 p = c.project({10, -3, 5});
    CHECK(p.x == doctest::Approx(200));
    CHECK(p.y == doctest::Approx(125));
    const Vec3 top = c.project({10, -1, 5});  // 2 units up: 2 * scale pixels above the centre
    CHECK(top.y == doctest::Approx(125 - 2 * c.scale));
    CHECK(c.project({10, -3, 7}).z > c.project({10, -3, 3}).z);  // nearer is larger
}

// ---- coverage and visibility ---------------------------------------------------------------------

TEST_CASE("a cube seen from the front covers exactly its projected square") {
    const IndexedMesh m = cube();
    RenderOptions o = small(240, 180);
    const Image img = nmesh::render(m, o);
    REQUIRE(img.width == 240);
    REQUIRE(img.height == 180);
    REQUIRE(img.rgb.size() == 240u * 180u * 3u);
    const Camera cam = nmesh::frame_camera(m, o);
    const Vec3 lo = cam.project({-1, 1, 1}), hi = cam.project({1, -1, 1});  // top-left, bottom-right
    CHECK(covered(img, 120, 90));
    CHECK_FALSE(covered(img, 0, 0));
    CHECK_FALSE(covered(img, 239, 179));
    int wrong = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const double cx = x + 0.5, cy = y + 0.5;
            const bool inside = cx > lo.x && cx < hi.x && cy > lo.y && cy < hi.y;
            const bool on_border = std::fabs(cx - lo.x) < 0.01 || std::fabs(cx - hi.x) < 0.01 ||
                                   std::fabs(cy - lo.y) < 0.01 || std::fabs(cy - hi.y) < 0.01;
            if (!on_border && inside != covered(img, x, y)) ++wrong;
        }
    }
    CHECK(wrong == 0);
    const double side = 2 * cam.scale;  // the square's side in pixels
    CHECK(double(covered_count(img)) == doctest::Approx(side * side).epsilon(0.02));
}

TEST_CASE("triangles sharing edges leave no gaps") {
    // A square cut into a jittered 24 x 24 grid of 1152 triangles, seen face on: every pixel
    // centre inside the square must be covered.
    IndexedMesh m;
    const int n = 24;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const bool inner = i > 0 && i < n && j > 0 && j < n;
            m.positions.push_back(
                {(i + (inner ? jitter(rng) : 0.0f)) / n * 2 - 1, (j + (inner ? jitter(rng) : 0.0f)) / n * 2 - 1, 0.0f});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 2,
                                d = a + std::uint32_t(n) + 1;
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    const RenderOptions o = small(300, 300);
    const Image img = nmesh::render(m, o);
    const Camera cam = nmesh::frame_camera(m, o);
    const Vec3 lo = cam.project({-1, 1, 0}), hi = cam.project({1, -1, 0});
    int holes = 0, inside = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (x + 0.5 > lo.x + 0.01 && x + 0.5 < hi.x - 0.01 && y + 0.5 > lo.y + 0.01 && y + 0.5 < hi.y - 0.01) {
                ++inside;
                holes += !covered(img, x, y);
            }
    CHECK(inside > 30000);
    CHECK(holes == 0);
}

TEST_CASE("the z-buffer shows the nearer surface whatever the triangle order") {
    const IndexedMesh big = cube();
    for (const float z : {1.5f, -1.5f}) {
        CAPTURE(z);
        IndexedMesh m = merged(big, box({0, 0, z}, {0.3f, 0.3f, 0.3f}));
        // Value 0 on the big cube, 1 on the small one: the colour tells which one is seen.
        std::vector<float> values(m.positions.size(), 0.0f);
        std::fill(values.begin() + 8, values.end(), 1.0f);
        RenderOptions o = small();
        o.smooth = false;
        o.vertex_values = &values;
        const Image img = nmesh::render(m, o);
        const Rgb centre = img.pixel(100, 100);
        if (z > 0)
            CHECK(centre[0] > centre[2]);  // red: the small cube in front
        else
            CHECK(centre[2] > centre[0]);  // blue: the big cube hides the small one
        std::reverse(m.triangles.begin(), m.triangles.end());
        CHECK(nmesh::render(m, o).rgb == img.rgb);
    }
}

TEST_CASE("back faces are lit like front faces, in the back colour") {
    const RenderOptions defaults;
    CHECK(defaults.color == Rgb{0xBE, 0xC8, 0xDC});
    CHECK(defaults.back_color == Rgb{0xE0, 0xB0, 0x90});
    // A tetrahedron turned inside out shows only back faces: the image of the outward one with the
    // two colours swapped.
    IndexedMesh m = tetrahedron();
    IndexedMesh flipped = m;
    for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
    const Rgb a{200, 60, 30}, b{30, 90, 210};
    for (const bool smooth : {true, false}) {
        CAPTURE(smooth);
        RenderOptions o = small();
        o.smooth = smooth;
        o.view = View::iso();
        o.color = a;
        o.back_color = b;
        const Image out = nmesh::render(m, o);
        CHECK(covered_count(out) > 1000);
        o.color = b;
        o.back_color = a;
        CHECK(nmesh::render(flipped, o).rgb == out.rgb);
        CHECK(nmesh::render(m, o).rgb != out.rgb);
    }
    // One triangle seen from behind covers the same pixels as seen from the front, lit alike, in
    // the back colour's hue instead of the surface's.
    IndexedMesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0.3f, 0.9f, 0}};  // no pixel centre on an edge
    tri.triangles = {{0, 1, 2}};
    for (const bool smooth : {true, false}) {
        CAPTURE(smooth);
        RenderOptions o = small();
        o.smooth = smooth;
        const Image front = nmesh::render(tri, o);
        o.view = {180.0, 0.0};
        const Image back = nmesh::render(tri, o);
        CHECK(covered_count(front) > 5000);
        CHECK(covered_count(back) == covered_count(front));
        const Rgb f = front.pixel(100, 100), r = back.pixel(100, 100);
        double front_shade = 0, back_shade = 0;
        CHECK(has_hue(f, o.color, &front_shade));
        CHECK_FALSE(has_hue(f, o.back_color));
        CHECK(f[2] > f[0]);  // cool
        CHECK(has_hue(r, o.back_color, &back_shade));
        CHECK_FALSE(has_hue(r, o.color));
        CHECK(r[0] > r[2]);  // warm
        CHECK(front_shade > 0.5);
        CHECK(back_shade == doctest::Approx(front_shade).epsilon(0.02));
        o.back_color = {0, 255, 0};
        const Image green = nmesh::render(tri, o);
        CHECK(has_hue(green.pixel(100, 100), {0, 255, 0}));
        o.view = View::front();
        CHECK(nmesh::render(tri, o).rgb == front.rgb);  // the back colour does not reach the front
    }
}

TEST_CASE("an open surface shows its inside in the back colour") {
    // The sphere without its front cap: through the hole, the inside of the far wall; around it,
    // the outside of the remaining band.
    const IndexedMesh m = open_sphere(12);
    RenderOptions o = small();
    const Image img = nmesh::render(m, o);
    const Camera cam = nmesh::frame_camera(m, o);
    const Vec3 centre = cam.project({0, 0, 0});
    CHECK(has_hue(img.pixel(int(centre.x), int(centre.y)), o.back_color));
    const Vec3 band = cam.project({-0.9f, 0, 0});  // on the outside, left of the hole
    CHECK(has_hue(img.pixel(int(band.x), int(band.y)), o.color));
    // From behind, the closed side hides the inside: the back colour shows nowhere.
    o.view = {180.0, 0.0};
    const Image behind = nmesh::render(m, o);
    o.back_color = {255, 0, 0};
    CHECK(nmesh::render(m, o).rgb == behind.rgb);
}

TEST_CASE("a closed mesh seen from outside shows no back face") {
    // Rendered with a glaring back colour and with the surface colour as back colour, the images
    // must be the same, pixel for pixel.
    const std::vector<View> views = {View::front(),  View::side(), View::top(),  View::iso(),
                                     {200.0, -30.0}, {33.0, 71.0}, {301.0, -5.0}};
    const IndexedMesh meshes[] = {tetrahedron(), cube(), sphere(6),
                                  merged(cube(), box({0, 0, 1.5f}, {0.3f, 0.3f, 0.3f}))};
    for (std::size_t i = 0; i < std::size(meshes); ++i) {
        for (const View& view : views) {
            for (const int ss : {1, 3}) {
                for (const bool smooth : {true, false}) {
                    CAPTURE(i);
                    CAPTURE(view.azimuth_deg);
                    CAPTURE(view.elevation_deg);
                    CAPTURE(ss);
                    CAPTURE(smooth);
                    RenderOptions o = small(150, 120);
                    o.view = view;
                    o.supersample = ss;
                    o.smooth = smooth;
                    o.back_color = o.color;
                    const Image plain = nmesh::render(meshes[i], o);
                    o.back_color = {255, 0, 0};
                    CHECK(nmesh::render(meshes[i], o).rgb == plain.rgb);
                }
            }
        }
    }
    // Along the octahedron's outline, seen from the front, each back face meets a front face at
    // exactly the same depth, and the sample centres on the outline are covered by both: the front
    // face must win although the back faces come first. The bounding sphere's radius is 1, so the
    // scale is 0.9 * 201 / 2 pixels per unit and r puts the corners 45 pixels from the centre, on
    // a pixel centre; supersample 1, so every sample on the outline is a pixel.
    const float r = float(45.0 / (0.45 * 201.0));
    IndexedMesh oct = octahedron(r, 1.0f);
    for (const bool reversed : {false, true}) {
        CAPTURE(reversed);
        if (reversed) std::reverse(oct.triangles.begin(), oct.triangles.end());
        for (const bool smooth : {true, false}) {
            CAPTURE(smooth);
            RenderOptions o = small(201, 201);
            o.smooth = smooth;
            o.back_color = o.color;
            const Image plain = nmesh::render(oct, o);
            CHECK(covered(plain, 100 + 44, 100));
            CHECK_FALSE(covered(plain, 100 + 46, 100));
            o.back_color = {255, 0, 0};
            const Image marked = nmesh::render(oct, o);
            int back = 0;
            for (int y = 0; y < marked.height; ++y)
                for (int x = 0; x < marked.width; ++x) back += marked.pixel(x, y) != plain.pixel(x, y);
            CHECK(back == 0);
        }
    }
}

// ---- shading ---------------------------------------------------------------------------------------

TEST_CASE("the light comes from the camera's upper left") {
    // A sphere: the brightest pixel is up and to the left of its centre.
    const IndexedMesh s = sphere(12);
    for (const View view : {View::front(), View::side(), View{200.0, -30.0}}) {
        RenderOptions o = small();
        o.view = view;
        const Image img = nmesh::render(s, o);
        int best = -1, bx = 0, by = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const Rgb c = img.pixel(x, y);
                if (c == Rgb{255, 255, 255}) continue;
                if (c[0] + c[1] + c[2] > best) best = c[0] + c[1] + c[2], bx = x, by = y;
            }
        CHECK(bx < 100 - 10);
        CHECK(by < 100 - 10);
    }
    // A cube from the iso view: the top face is the brightest, the left face (+z) brighter than
    // the right one (+x).
    const IndexedMesh m = cube();
    RenderOptions o = small();
    o.view = View::iso();
    o.smooth = false;
    const Image img = nmesh::render(m, o);
    const Camera cam = nmesh::frame_camera(m, o);
    const auto brightness = [&](const Vec3& p) {
        const Vec3 q = cam.project(p);
        const Rgb c = img.pixel(int(q.x), int(q.y));
        return c[0] + c[1] + c[2];
    };
    const Vec3 top_face{0, 1, 0}, left_face{0, 0, 1}, right_face{1, 0, 0};
    CHECK(cam.project(left_face).x < cam.project(right_face).x);
    CHECK(brightness(top_face) > brightness(left_face));
    CHECK(brightness(left_face) > brightness(right_face));
}

TEST_CASE("flat shading gives one colour per triangle, smooth shading a gradient") {
    const IndexedMesh s = sphere(4);  // 96 triangles
    RenderOptions o = small();
    o.smooth = false;
    const Image flat = nmesh::render(s, o);
    std::set<Rgb> flat_colors;
    for (int y = 0; y < flat.height; ++y)
        for (int x = 0; x < flat.width; ++x) flat_colors.insert(flat.pixel(x, y));
    CHECK(flat_colors.size() <= 96 + 1);  // visible triangles, plus the background
    CHECK(flat_colors.size() > 10);
    o.smooth = true;
    const Image smooth = nmesh::render(s, o);
    std::set<Rgb> smooth_colors;
    for (int y = 0; y < smooth.height; ++y)
        for (int x = 0; x < smooth.width; ++x) smooth_colors.insert(smooth.pixel(x, y));
    CHECK(smooth_colors.size() > 4 * flat_colors.size());
    CHECK(covered_count(smooth) == covered_count(flat));
}

TEST_CASE("the wireframe darkens the visible edges and nothing else") {
    const IndexedMesh m = cube();
    RenderOptions o = small();
    o.smooth = false;
    const Image plain = nmesh::render(m, o);
    o.wireframe = true;
    const Image wire = nmesh::render(m, o);
    const Camera cam = nmesh::frame_camera(m, o);
    // The edges of the front face (z = 1): the square's sides and the diagonal its two triangles
    // share.
    std::vector<std::array<Vec3, 2>> edges;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const auto& t : m.triangles) {
        if (m.positions[t[0]].z < 1 || m.positions[t[1]].z < 1 || m.positions[t[2]].z < 1) continue;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = t[k], b = t[(k + 1) % 3];
            if (uses[{std::min(a, b), std::max(a, b)}]++ == 0)
                edges.push_back({cam.project(m.positions[a]), cam.project(m.positions[b])});
        }
    }
    REQUIRE(edges.size() == 5);
    std::array<Vec3, 2> diagonal_edge{};
    for (const auto& [edge, count] : uses)
        if (count == 2) diagonal_edge = {cam.project(m.positions[edge.first]), cam.project(m.positions[edge.second])};
    const Vec3 lo = cam.project({-1, 1, 1}), hi = cam.project({1, -1, 1});

    // Inside the face, each pixel is the plain colour darkened to 20% at an edge, fading linearly
    // to no change one pixel away; outside it, nothing changes.
    const Rgb face = plain.pixel(100, 100);
    int mismatches = 0, darkened = 0, on_diagonal = 0;
    for (int y = 0; y < wire.height; ++y)
        for (int x = 0; x < wire.width; ++x) {
            const double cx = x + 0.5, cy = y + 0.5;
            const bool inside = cx > lo.x + 0.01 && cx < hi.x - 0.01 && cy > lo.y + 0.01 && cy < hi.y - 0.01;
            const bool outside = cx < lo.x - 0.01 || cx > hi.x + 0.01 || cy < lo.y - 0.01 || cy > hi.y + 0.01;
            const Rgb got = wire.pixel(x, y);
            if (outside) {
                mismatches += got != plain.pixel(x, y);
                continue;
            }
            if (!inside) continue;
            double d = 1e9;
            for (const auto& e : edges) d = std::min(d, distance_to_segment(cx, cy, e[0], e[1]));
            const double keep = 1.0 - 0.8 * std::max(0.0, 1.0 - d);
            for (int i = 0; i < 3; ++i) mismatches += std::fabs(got[i] - face[i] * keep) > 1.5;
            if (keep <= 0.6) {
                ++darkened;
                on_diagonal += distance_to_segment(cx, cy, diagonal_edge[0], diagonal_edge[1]) < 0.5;
            }
        }
    CHECK(mismatches == 0);
    const double side = 2 * cam.scale;
    CHECK(on_diagonal > 0.95 * side);  // at least one strongly darkened pixel per row
    CHECK(darkened > on_diagonal);     // and more along the square's sides
    CHECK(covered_count(wire) == covered_count(plain));
}

TEST_CASE("vertex values colour the surface through the ramp") {
    CHECK(nmesh::ramp_color(0.0)[2] > nmesh::ramp_color(0.0)[0]);
    CHECK(nmesh::ramp_color(1.0)[0] > nmesh::ramp_color(1.0)[2]);
    const Rgb mid = nmesh::ramp_color(0.5);
    CHECK(mid[1] > mid[0]);
    CHECK(mid[1] > mid[2]);
    CHECK(nmesh::ramp_color(-3.0) == nmesh::ramp_color(0.0));
    CHECK(nmesh::ramp_color(7.0) == nmesh::ramp_color(1.0));

    const IndexedMesh m = cube();
    RenderOptions o = small();
    const Image plain = nmesh::render(m, o);
    // Values growing with x: blue on the left of the front face, red on the right.
    std::vector<float> values;
    for (const Vec3& p : m.positions) values.push_back(p.x);
    o.vertex_values = &values;
    const Image by_x = nmesh::render(m, o);
    CHECK(by_x.rgb != plain.rgb);
    CHECK(covered_count(by_x) == covered_count(plain));
    const Rgb left = by_x.pixel(50, 100), right = by_x.pixel(150, 100);
    CHECK(left[2] > left[0]);
    CHECK(right[0] > right[2]);
    // A given range: values at its middle are green everywhere; above it, clamped to red.
    std::vector<float> fives(m.positions.size(), 5.0f);
    o.vertex_values = &fives;
    o.value_min = 0.0f;
    o.value_max = 10.0f;
    const Image green = nmesh::render(m, o);
    const Rgb g = green.pixel(100, 100);
    CHECK(g[1] > g[0]);
    CHECK(g[1] > g[2]);
    o.value_max = 2.0f;
    const Rgb r = nmesh::render(m, o).pixel(100, 100);
    CHECK(r[0] > r[1]);
    CHECK(r[0] > r[2]);
}

TEST_CASE("vertex values keep their colours on back faces, darkened") {
    IndexedMesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0.3f, 0.9f, 0}};
    tri.triangles = {{0, 1, 2}};
    const std::vector<float> values(3, 0.75f);  // yellow
    for (const bool smooth : {true, false}) {
        CAPTURE(smooth);
        RenderOptions o = small();
        o.smooth = smooth;
        o.vertex_values = &values;
        o.value_min = 0.0f;
        o.value_max = 1.0f;
        const Rgb yellow = nmesh::ramp_color(0.75);
        const Rgb front = nmesh::render(tri, o).pixel(100, 100);
        o.view = {180.0, 0.0};
        const Image back = nmesh::render(tri, o);
        const Rgb behind = back.pixel(100, 100);
        double front_shade = 0, back_shade = 0;
        CHECK(has_hue(front, yellow, &front_shade));
        CHECK(has_hue(behind, yellow, &back_shade));
        CHECK(back_shade == doctest::Approx(0.6 * front_shade).epsilon(0.02));
        o.back_color = {255, 0, 0};  // not used with vertex values
        CHECK(nmesh::render(tri, o).rgb == back.rgb);
    }
}

TEST_CASE("each view gives its own image, with the extents the view shows") {
    const IndexedMesh t = tetrahedron();
    std::vector<Bytes> images;
    for (const View v : {View::front(), View::side(), View::top(), View::iso()}) {
        RenderOptions o = small();
        o.view = v;
        images.push_back(nmesh::render(t, o).rgb);
    }
    for (std::size_t i = 0; i < images.size(); ++i)
        for (std::size_t j = i + 1; j < images.size(); ++j) CHECK(images[i] != images[j]);
    RenderOptions o = small();
    o.view = {90.0, 0.0};
    CHECK(nmesh::render(t, o).rgb == images[1]);

    // A box 4 long in x, 1 in y, 2 in z: its covered rectangle in each view.
    const IndexedMesh b = box({0, 0, 0}, {2, 0.5f, 1});
    const struct {
        View view;
        double w, h;  // extents in mesh units along the image's x and y
    } expected[] = {{View::front(), 4, 1}, {View::side(), 2, 1}, {View::top(), 4, 2}};
    for (const auto& e : expected) {
        RenderOptions ob = small(300, 300);
        ob.view = e.view;
        const Image img = nmesh::render(b, ob);
        const double s = nmesh::frame_camera(b, ob).scale;
        const auto box_px = covered_box(img);
        CHECK(box_px[2] - box_px[0] + 1 == doctest::Approx(e.w * s).epsilon(0.02));
        CHECK(box_px[3] - box_px[1] + 1 == doctest::Approx(e.h * s).epsilon(0.05));
    }
}

TEST_CASE("supersampling smooths the silhouette without moving it") {
    const IndexedMesh t = tetrahedron();
    RenderOptions o = small();
    o.smooth = false;
    o.view = View::iso();
    const Image one = nmesh::render(t, o);
    o.supersample = 3;
    const Image three = nmesh::render(t, o);
    // Pixels that are partly covered blend surface and background: colours the single-sample
    // image cannot have on a white background next to a flat facet.
    std::set<Rgb> one_colors, three_colors;
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) {
            one_colors.insert(one.pixel(x, y));
            three_colors.insert(three.pixel(x, y));
        }
    CHECK(one_colors.size() <= 5);  // at most four facets, and the background
    CHECK(one_colors.size() >= 3);
    CHECK(three_colors.size() > 20);  // blends of 1 to 8 samples in 9
    // Coverage, weighted by how far each pixel is from the background, barely changes.
    const auto weight = [](const Image& img) {
        double w = 0;
        for (std::size_t i = 0; i < img.rgb.size(); ++i) w += 255 - img.rgb[i];
        return w;
    };
    CHECK(weight(three) == doctest::Approx(weight(one)).epsilon(0.01));
}

TEST_CASE("render handles empty and degenerate meshes and refuses bad options") {
    RenderOptions o = small(20, 10);
    o.background = {1, 2, 3};
    const Image empty = nmesh::render(IndexedMesh{}, o);
    CHECK(empty.width == 20);
    CHECK(empty.height == 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x) CHECK(empty.pixel(x, y) == Rgb{1, 2, 3});
    IndexedMesh point;
    point.positions = {{1, 1, 1}};
    point.triangles = {{0, 0, 0}};
    CHECK(nmesh::render(point, o).rgb == empty.rgb);

    const IndexedMesh m = cube();
    RenderOptions bad = small();
    // Each refusal names the option (ParameterError::parameter()).
    const auto refused = [&](const RenderOptions& options) {
        return refused_parameter([&] { nmesh::render(m, options); });
    };
    bad.width = 0;
    CHECK(refused(bad) == "width");
    bad = small();
    bad.height = 16385;
    CHECK(refused(bad) == "height");
    bad = small();
    bad.supersample = 5;
    CHECK(refused(bad) == "supersample");
    bad = small();
    bad.view = {0.0, 91.0};
    CHECK(refused(bad) == "view.elevation_deg");
    bad = small();
    bad.view = {NAN, 0.0};
    CHECK(refused(bad) == "view.azimuth_deg");
    std::vector<float> too_few(3, 0.0f);
    bad = small();
    bad.vertex_values = &too_few;
    CHECK(refused(bad) == "vertex_values");
    std::vector<float> with_nan(8, 0.0f);
    with_nan[4] = NAN;
    bad.vertex_values = &with_nan;
    CHECK(refused(bad) == "vertex_values");
    std::vector<float> fine(8, 0.0f);
    bad.vertex_values = &fine;
    bad.value_min = 2.0f;
    bad.value_max = 1.0f;
    CHECK(refused(bad) == "value_min");
    bad.value_min.reset();
    bad.value_max = NAN;
    CHECK(refused(bad) == "value_max");
    IndexedMesh broken = m;
    broken.triangles[3][1] = 8;
    CHECK_THROWS_AS(nmesh::render(broken, small()), nmesh::InputError);
    broken = m;
    broken.positions[2].y = INFINITY;
    CHECK_THROWS_AS(nmesh::render(broken, small()), nmesh::InputError);
    broken.triangles.clear();  // the infinite vertex is unused now
    CHECK_NOTHROW(nmesh::render(broken, small()));
}

TEST_CASE("a rendered image survives the PNG round trip") {
    RenderOptions o;
    o.width = 320;
    o.height = 240;
    o.view = View::iso();
    o.wireframe = true;
    const Image img = nmesh::render(sphere(6), o);
    const Bytes png = nmesh::encode_png(img.width, img.height, img.rgb);
    const Decoded d = decode_png(png);
    CHECK(d.width == 320);
    CHECK(d.height == 240);
    CHECK(d.rgb == img.rgb);
    CHECK(png.size() < img.rgb.size() / 3);
}
