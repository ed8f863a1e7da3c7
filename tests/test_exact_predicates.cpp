// Tests of the exact orientation predicates: signs compared with an independent exact reference (a
// small big-integer evaluation of the determinant) on random, nearly degenerate and exactly
// degenerate inputs, including inputs where a plain double evaluation gets the sign wrong.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "nmesh/geometry/exact_predicates.h"
#include "nmesh/vec3.h"

using nmesh::orient2d;
using nmesh::orient3d;
using nmesh::Point2d;
using nmesh::Point3d;
using nmesh::Vec3;

namespace {

__extension__ typedef unsigned __int128 Wide;

// ---- the reference: integers of any size -------------------------------------------------------

// A signed integer of any size: a sign and a little-endian magnitude in 32-bit limbs, without
// leading zero limbs (zero has none).
struct BigInt {
    bool negative = false;
    std::vector<std::uint32_t> limbs;

    int sign() const { return limbs.empty() ? 0 : (negative ? -1 : 1); }
};

void trim(BigInt& a) {
    while (!a.limbs.empty() && a.limbs.back() == 0) a.limbs.pop_back();
    if (a.limbs.empty()) a.negative = false;
}

int compare_magnitudes(const BigInt& a, const BigInt& b) {
    if (a.limbs.size() != b.limbs.size()) return a.limbs.size() < b.limbs.size() ? -1 : 1;
    for (std::size_t i = a.limbs.size(); i-- > 0;)
        if (a.limbs[i] != b.limbs[i]) return a.limbs[i] < b.limbs[i] ? -1 : 1;
    return 0;
}

// |a| + |b|.
std::vector<std::uint32_t> add_magnitudes(const BigInt& a, const BigInt& b) {
    std::vector<std::uint32_t> r(std::max(a.limbs.size(), b.limbs.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i + 1 < r.size(); ++i) {
        const std::uint64_t s = carry + (i < a.limbs.size() ? a.limbs[i] : 0) + (i < b.limbs.size() ? b.limbs[i] : 0);
        r[i] = std::uint32_t(s);
        carry = s >> 32;
    }
    r.back() = std::uint32_t(carry);
    return r;
}

// |a| - |b|, given |a| >= |b|.
std::vector<std::uint32_t> subtract_magnitudes(const BigInt& a, const BigInt& b) {
    std::vector<std::uint32_t> r(a.limbs.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        std::int64_t d = std::int64_t(a.limbs[i]) - borrow - (i < b.limbs.size() ? std::int64_t(b.limbs[i]) : 0);
        borrow = d < 0 ? 1 : 0;
        if (d < 0) d += std::int64_t(1) << 32;
        r[i] = std::uint32_t(d);
    }
    return r;
}

BigInt operator+(const BigInt& a, const BigInt& b) {
    BigInt r;
    if (a.negative == b.negative) {
        r.limbs = add_magnitudes(a, b);
        r.negative = a.negative;
    } else if (compare_magnitudes(a, b) >= 0) {
        r.limbs = subtract_magnitudes(a, b);
        r.negative = a.negative;
    } else {
        r.limbs = subtract_magnitudes(b, a);
        r.negative = b.negative;
    }
    trim(r);
    return r;
}

BigInt operator-(const BigInt& a) {
    BigInt r = a;
    if (!r.limbs.empty()) r.negative = !r.negative;
    return r;
}

BigInt operator-(const BigInt& a, const BigInt& b) { return a + (-b); }

BigInt operator*(const BigInt& a, const BigInt& b) {
    BigInt r;
    r.limbs.assign(a.limbs.size() + b.limbs.size() + 1, 0);
    for (std::size_t i = 0; i < a.limbs.size(); ++i) {
        std::uint64_t carry = 0;
        for (std::size_t j = 0; j < b.limbs.size(); ++j) {
            const std::uint64_t t = std::uint64_t(a.limbs[i]) * b.limbs[j] + r.limbs[i + j] + carry;
            r.limbs[i + j] = std::uint32_t(t);
            carry = t >> 32;
        }
        for (std::size_t k = i + b.limbs.size(); carry != 0; ++k) {
            const std::uint64_t t = std::uint64_t(r.limbs[k]) + carry;
            r.limbs[k] = std::uint32_t(t);
            carry = t >> 32;
        }
    }
    r.negative = a.negative != b.negative;
    trim(r);
    return r;
}

// The exponent e of the lowest set bit of a double's significand: x = m 2^e with m an odd integer.
int low_exponent(double x) {
    int e = 0;
    const double m = std::frexp(std::fabs(x), &e);  // |x| = m 2^e, m in [0.5, 1)
    std::uint64_t bits = std::uint64_t(std::ldexp(m, 53));
    e -= 53;
    while ((bits & 1) == 0) {
        bits >>= 1;
        ++e;
    }
    return e;
}

// The integer x 2^shift, which must be an integer.
BigInt scaled_integer(double x, int shift) {
    BigInt r;
    if (x == 0.0) return r;
    int e = 0;
    const double m = std::frexp(std::fabs(x), &e);
    const std::uint64_t significand = std::uint64_t(std::ldexp(m, 53));
    int exponent = e - 53 + shift;
    std::uint64_t bits = significand;
    while (exponent < 0) {
        if ((bits & 1) != 0) throw std::logic_error("scaled_integer: not an integer");
        bits >>= 1;
        ++exponent;
    }
    r.limbs.assign(std::size_t(exponent / 32) + 3, 0);
    const int limb = exponent / 32, offset = exponent % 32;
    const Wide wide = Wide(bits) << offset;
    r.limbs[std::size_t(limb)] = std::uint32_t(wide);
    r.limbs[std::size_t(limb) + 1] = std::uint32_t(wide >> 32);
    r.limbs[std::size_t(limb) + 2] = std::uint32_t(wide >> 64);
    r.negative = x < 0.0;
    trim(r);
    return r;
}

// The coordinates as integers, all scaled by the same power of two (which keeps every sign).
std::vector<BigInt> common_scale(const std::vector<double>& xs) {
    int lowest = 0;
    bool any = false;
    for (double x : xs)
        if (x != 0.0) {
            lowest = any ? std::min(lowest, low_exponent(x)) : low_exponent(x);
            any = true;
        }
    std::vector<BigInt> r;
    for (double x : xs) r.push_back(scaled_integer(x, -lowest));
    return r;
}

int reference_orient2d(const Point2d& a, const Point2d& b, const Point2d& c) {
    const std::vector<BigInt> v = common_scale({a.x, a.y, b.x, b.y, c.x, c.y});
    const BigInt acx = v[0] - v[4], acy = v[1] - v[5], bcx = v[2] - v[4], bcy = v[3] - v[5];
    return (acx * bcy - acy * bcx).sign();
}

int reference_orient3d(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const std::vector<BigInt> v = common_scale({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z});
    BigInt m[3][3];
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) m[r][k] = v[std::size_t(3 * r + k)] - v[std::size_t(9 + k)];
    const BigInt det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return det.sign();
}

// ---- plain double evaluations, for contrast ----------------------------------------------------

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

int naive_orient2d(const Point2d& a, const Point2d& b, const Point2d& c) {
    return sign_of((a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x));
}

int naive_orient3d(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const double adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
    const double bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
    const double cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
    return sign_of(adx * (bdy * cdz - bdz * cdy) - ady * (bdx * cdz - bdz * cdx) + adz * (bdx * cdy - bdy * cdx));
}

// ---- inputs ------------------------------------------------------------------------------------

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
int uniform_int(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// x moved by k units in the last place.
double ulps(double x, int k) {
    for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
    for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
    return x;
}

// A small integer times a power of two in [lowest, highest].
double scaled_small(Rng& rng, int lowest, int highest) {
    return std::ldexp(double(uniform_int(rng, -(1 << 20), 1 << 20)), uniform_int(rng, lowest, highest));
}

Point3d random_point(Rng& rng, double lo, double hi) {
    return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}

// A point near the plane of a, b, c: an affine combination rounded in double, then each coordinate
// moved by up to `spread` units in the last place.
Point3d near_plane(Rng& rng, const Point3d& a, const Point3d& b, const Point3d& c, int spread) {
    const double u = uniform(rng, -1.0, 2.0), v = uniform(rng, -1.0, 2.0);
    Point3d d{a.x + u * (b.x - a.x) + v * (c.x - a.x), a.y + u * (b.y - a.y) + v * (c.y - a.y),
              a.z + u * (b.z - a.z) + v * (c.z - a.z)};
    d.x = ulps(d.x, uniform_int(rng, -spread, spread));
    d.y = ulps(d.y, uniform_int(rng, -spread, spread));
    d.z = ulps(d.z, uniform_int(rng, -spread, spread));
    return d;
}

// Tallies of one family of inputs.
struct Tally {
    int cases = 0, wrong = 0, naive_wrong = 0, zeros = 0;
};

void record3(Tally& t, const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const int reference = reference_orient3d(a, b, c, d);
    const int exact = orient3d(a, b, c, d);
    ++t.cases;
    if (exact != reference) ++t.wrong;
    if (naive_orient3d(a, b, c, d) != reference) ++t.naive_wrong;
    if (reference == 0) ++t.zeros;
    // Exchanging two points flips the sign; a cyclic shift of a, b, c keeps it.
    if (orient3d(b, a, c, d) != -reference || orient3d(a, b, d, c) != -reference || orient3d(b, c, a, d) != reference)
        ++t.wrong;
}

void record2(Tally& t, const Point2d& a, const Point2d& b, const Point2d& c) {
    const int reference = reference_orient2d(a, b, c);
    ++t.cases;
    if (orient2d(a, b, c) != reference) ++t.wrong;
    if (naive_orient2d(a, b, c) != reference) ++t.naive_wrong;
    if (reference == 0) ++t.zeros;
    if (orient2d(b, a, c) != -reference || orient2d(b, c, a) != reference || orient2d(a, c, b) != -reference) ++t.wrong;
}

}  // namespace

TEST_CASE("exact predicates: the reference itself on known determinants") {
    // Shewchuk's convention: positive for d below the counter-clockwise triangle abc.
    const Point3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    CHECK(reference_orient3d(a, b, c, {0, 0, -1}) == 1);
    CHECK(reference_orient3d(a, b, c, {0.25, 0.25, 3}) == -1);
    CHECK(reference_orient3d(a, b, c, {7, -5, 0}) == 0);
    CHECK(reference_orient2d({0, 0}, {1, 0}, {0, 1}) == 1);
    CHECK(reference_orient2d({0, 0}, {0, 1}, {1, 0}) == -1);
    CHECK(reference_orient2d({0, 0}, {1, 1}, {3, 3}) == 0);
    // Determinants of -2^-52, of about 1 - 3 2^-60, of 0 and of -2^-40.
    const double tiny = std::ldexp(1.0, -60);
    CHECK(reference_orient2d({0, 0}, {1, 1}, {1 + std::ldexp(1.0, -52), 1}) == -1);
    CHECK(reference_orient3d({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {tiny, tiny, tiny}) == 1);
    const double t40 = std::ldexp(1.0, -40);  // 1 - 2^-39 is a double, 1 - 2^-59 is not
    CHECK(reference_orient3d({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1 - 2 * t40, t40, t40}) == 0);
    CHECK(reference_orient3d({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1 - 2 * t40, t40, 2 * t40}) == -1);
    // Big integers: (2^64 + 1)^2 - 2^128 = 2^65 + 1.
    const BigInt x = scaled_integer(std::ldexp(1.0, 64), 0) + scaled_integer(1.0, 0);
    const BigInt y = x * x - scaled_integer(std::ldexp(1.0, 128), 0);
    CHECK(y.sign() == 1);
    CHECK((y - scaled_integer(std::ldexp(1.0, 65), 0) - scaled_integer(1.0, 0)).sign() == 0);
}

TEST_CASE("exact predicates: orientation conventions") {
    const Point3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    CHECK(orient3d(a, b, c, {0, 0, -1}) == 1);
    CHECK(orient3d(a, b, c, {0.3, 0.3, 1e-300}) == -1);
    CHECK(orient3d(a, b, c, {5, 9, 0}) == 0);
    CHECK(orient2d({0, 0}, {1, 0}, {0, 1}) == 1);
    CHECK(orient2d({0, 0}, {1, 0}, {5, 0}) == 0);
    CHECK(orient2d({0, 0}, {1, 0}, {5, -1e-300}) == -1);
    const Vec3 fa{0, 0, 0}, fb{1, 0, 0}, fc{0, 1, 0};
    CHECK(orient3d(fa, fb, fc, Vec3{0, 0, -1}) == 1);
    CHECK(orient3d(fa, fb, fc, Vec3{0, 0, 1e-30f}) == -1);
}

TEST_CASE("exact predicates: single roundings that decide the sign") {
    // Inputs whose differences and products are exact in double but where one addition rounds
    // and that rounding is the whole determinant: a plain evaluation gives 0.
    const double big = std::ldexp(1.0, 60), k = std::ldexp(1.0, 30);
    struct Case {
        Point3d a, b, c, d;
        int sign;
    };
    const Case cases[] = {
        // The terms are 2^60, 1 and -2^60: their first sum rounds.
        {{1, 0, -big}, {0, 1, -1}, {1, 1, -big}, {0, 0, 0}, 1},
        // The minor 2^30 2^30 - 1 rounds; the other terms cancel its rounded value.
        {{0, 1, 1}, {k, 1, 0}, {1, k, k}, {0, 0, 0}, -1},
        // The same, moved away from the origin by an exactly representable offset.
        {{8, 9, 9}, {k + 8, 9, 8}, {9, k + 8, k + 8}, {8, 8, 8}, -1},
    };
    for (const Case& c : cases) {
        CHECK(reference_orient3d(c.a, c.b, c.c, c.d) == c.sign);
        CHECK(naive_orient3d(c.a, c.b, c.c, c.d) == 0);
        CHECK(orient3d(c.a, c.b, c.c, c.d) == c.sign);
        CHECK(orient3d(c.b, c.a, c.c, c.d) == -c.sign);
    }
    // 2D: (2^30 + 1)(2^30 - 1) - 2^30 2^30 = -1, where the first product rounds to 2^60.
    const Point2d p{k + 1, k}, q{k, k - 1}, o{0, 0};
    CHECK(reference_orient2d(p, q, o) == -1);
    CHECK(naive_orient2d(p, q, o) == 0);
    CHECK(orient2d(p, q, o) == -1);
}

TEST_CASE("exact predicates: random well-conditioned inputs agree with the reference") {
    Rng rng(1);
    Tally t3, t2;
    for (int i = 0; i < 4000; ++i) {
        record3(t3, random_point(rng, -1, 1), random_point(rng, -1, 1), random_point(rng, -1, 1),
                random_point(rng, -1, 1));
        record2(t2, {uniform(rng, -1, 1), uniform(rng, -1, 1)}, {uniform(rng, -1, 1), uniform(rng, -1, 1)},
                {uniform(rng, -1, 1), uniform(rng, -1, 1)});
    }
    CHECK(t3.wrong == 0);
    CHECK(t2.wrong == 0);
}

TEST_CASE("exact predicates: small integers times powers of two (inexact differences)") {
    // Mixed exponents make the differences inexact in double, which exercises the two-component
    // differences of the exact stage; a narrow exponent range makes many cases exactly degenerate.
    Rng rng(2);
    for (const int spread : {0, 3, 40, 200}) {
        Tally t3, t2;
        for (int i = 0; i < 3000; ++i) {
            const auto s = [&] { return scaled_small(rng, -spread, spread); };
            // Exactly degenerate quarter: d repeats a coordinate pattern of a, b, c.
            Point3d a{s(), s(), s()}, b{s(), s(), s()}, c{s(), s(), s()}, d{s(), s(), s()};
            if (i % 4 == 0) d = {a.x, b.y, a.z};
            if (i % 8 == 1) a.z = b.z = c.z = d.z;  // coplanar: one horizontal plane
            record3(t3, a, b, c, d);
            Point2d p{s(), s()}, q{s(), s()}, r{s(), s()};
            if (i % 4 == 0) r = {p.x, q.y};
            if (i % 8 == 1) p.y = q.y = r.y;  // collinear
            record2(t2, p, q, r);
        }
        INFO("exponent spread " << spread);
        CHECK(t3.wrong == 0);
        CHECK(t2.wrong == 0);
        CHECK(t3.zeros > 0);
        CHECK(t2.zeros > 0);
    }
}

TEST_CASE("exact predicates: extreme magnitudes within the documented range") {
    Rng rng(3);
    Tally t3, t2;
    for (int i = 0; i < 2000; ++i) {
        // |x| in [2^-256, 2^256]: small integers below 2^21 times 2^e, e in [-256, 235].
        const auto s = [&] {
            const int m = uniform_int(rng, 1, (1 << 20)) * (uniform_int(rng, 0, 1) ? 1 : -1);
            return std::ldexp(double(m), uniform_int(rng, -256, 235));
        };
        const Point3d a{s(), s(), s()}, b{s(), s(), s()}, c{s(), s(), s()};
        record3(t3, a, b, c, {s(), s(), s()});
        record3(t3, a, b, c, {a.x, b.y, c.z});
        record3(t3, a, b, {a.x, b.y, s()}, {b.x, a.y, s()});
        record2(t2, {a.x, a.y}, {b.x, b.y}, {c.x, c.y});
        record2(t2, {a.x, a.y}, {b.x, b.y}, {a.x, b.y});
        // Exactly coplanar (the plane x = y) and collinear (the line x = y), with inexact
        // differences.
        const double p = s(), q = s(), r = s();
        record3(t3, {a.x, a.x, a.y}, {b.x, b.x, b.y}, {c.x, c.x, c.y}, {p, p, q});
        record2(t2, {a.x, a.x}, {r, r}, {q, q});
    }
    CHECK(t3.wrong == 0);
    CHECK(t2.wrong == 0);
    CHECK(t3.zeros >= 2000);
    CHECK(t2.zeros >= 2000);
}

TEST_CASE("exact predicates: nearly coplanar points, where double evaluation fails") {
    Rng rng(4);
    // Triangles of size `scale` at distance `offset` from the origin, and points near their plane
    // (an affine combination rounded, then moved by up to one unit in the last place). The point's
    // distance to the plane is then of the order of its rounding, |offset + scale| 2^-53, and the
    // rounding error of the double evaluation is of the order of scale^3 2^-53: a double
    // evaluation fails on such inputs when the triangle is about as large as its distance to the
    // origin, and the exact predicate must not fail on any.
    struct Family {
        double offset, scale;
        bool naive_fails;
    };
    for (const Family f : {Family{0, 1, true}, Family{0, 1e6, true}, Family{1e6, 1e6, true}, Family{3e9, 1, false}}) {
        Tally t;
        for (int i = 0; i < 3000; ++i) {
            const Point3d o{f.offset, f.offset * 0.7, -f.offset * 1.3};
            const auto p = [&] {
                const Point3d r = random_point(rng, -f.scale, f.scale);
                return Point3d{o.x + r.x, o.y + r.y, o.z + r.z};
            };
            const Point3d a = p(), b = p(), c = p();
            record3(t, a, b, c, near_plane(rng, a, b, c, i % 2 == 0 ? 1 : 0));
        }
        INFO("offset " << f.offset << ", scale " << f.scale << ": naive wrong in " << t.naive_wrong << " of "
                       << t.cases);
        CHECK(t.wrong == 0);
        if (f.naive_fails) CHECK(t.naive_wrong > 0);
    }
}

TEST_CASE("exact predicates: exactly coplanar points far from the origin") {
    // Lattice points o + i u + j v with o about 1e6 and u, v of order 1 (all exactly representable):
    // the determinant is exactly 0, yet rounding usually leaves a double evaluation nonzero.
    // One unit in the last place off the plane, the sign must follow the move.
    Rng rng(5);
    Tally t, moved;
    for (int i = 0; i < 3000; ++i) {
        const Point3d o{1e6 + uniform_int(rng, 0, 1000), 1e6 - uniform_int(rng, 0, 1000), 2e6};
        const auto small = [&] { return std::ldexp(double(uniform_int(rng, -4096, 4096)), -10); };
        const Point3d u{small(), small(), small()}, v{small(), small(), small()};
        const auto at = [&](int ii, int jj) {
            return Point3d{o.x + ii * u.x + jj * v.x, o.y + ii * u.y + jj * v.y, o.z + ii * u.z + jj * v.z};
        };
        const auto k = [&] { return uniform_int(rng, -50, 50); };
        const Point3d a = at(k(), k()), b = at(k(), k()), c = at(k(), k()), d = at(k(), k());
        record3(t, a, b, c, d);
        record3(moved, a, b, c, {d.x, d.y, ulps(d.z, i % 2 == 0 ? 1 : -1)});
        // The 2D analogue: collinear lattice points.
        const Point3d p = at(k(), 0), q = at(k(), 0), r = at(k(), 0);
        record2(t, {p.x, p.y}, {q.x, q.y}, {r.x, r.y});
    }
    INFO("naive wrong: coplanar " << t.naive_wrong << " of " << t.cases << ", moved " << moved.naive_wrong);
    CHECK(t.wrong == 0);
    CHECK(moved.wrong == 0);
    CHECK(t.zeros > 2000);
    CHECK(t.naive_wrong > 0);
    CHECK(moved.naive_wrong > 0);
}

TEST_CASE("exact predicates: nearly collinear 2D points, where double evaluation fails") {
    Rng rng(6);
    for (const double offset : {0.0, 1e8}) {
        Tally t;
        for (int i = 0; i < 4000; ++i) {
            const double scale = offset + 1.0;
            const Point2d a{offset + uniform(rng, -scale, scale), uniform(rng, -scale, scale)};
            const Point2d b{offset + uniform(rng, -scale, scale), uniform(rng, -scale, scale)};
            const double s = uniform(rng, -1, 2);
            Point2d c{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
            c.x = ulps(c.x, uniform_int(rng, -1, 1));
            record2(t, a, b, c);
        }
        INFO("offset " << offset << ": naive wrong in " << t.naive_wrong << " of " << t.cases);
        CHECK(t.wrong == 0);
        CHECK(t.naive_wrong > 0);
    }
}

TEST_CASE("exact predicates: float positions (the Vec3 overload)") {
    // Floats convert to doubles exactly; nearly coplanar float points, a few float ulps off a
    // plane, around unit size and far from the origin.
    Rng rng(7);
    for (const float offset : {0.0f, 1000.0f, 1e6f}) {
        Tally t;
        for (int i = 0; i < 3000; ++i) {
            const auto p = [&] {
                return Vec3{offset + float(uniform(rng, -1, 1)), offset + float(uniform(rng, -1, 1)),
                            offset + float(uniform(rng, -1, 1))};
            };
            const Vec3 a = p(), b = p(), c = p();
            const float u = float(uniform(rng, -1, 2)), v = float(uniform(rng, -1, 2));
            Vec3 d = a + (b - a) * u + (c - a) * v;
            for (int k = 0; k < 3; ++k)
                for (int n = uniform_int(rng, -2, 2); n != 0; n += (n > 0 ? -1 : 1))
                    d[k] = std::nextafter(d[k], n > 0 ? HUGE_VALF : -HUGE_VALF);
            const Point3d pa = nmesh::to_point3d(a), pb = nmesh::to_point3d(b), pc = nmesh::to_point3d(c),
                          pd = nmesh::to_point3d(d);
            record3(t, pa, pb, pc, pd);
            if (orient3d(a, b, c, d) != orient3d(pa, pb, pc, pd)) ++t.wrong;
        }
        INFO("offset " << offset << ": naive wrong in " << t.naive_wrong << " of " << t.cases);
        CHECK(t.wrong == 0);
    }
}
