#include "nmesh/geometry/exact_predicates.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace nmesh {

namespace {

// ---- error-free transformations ----------------------------------------------------------------
// Each returns the rounded result and stores in `lo` its rounding error, so that the result plus
// lo is exactly the real sum, difference or product (Knuth's Two-Sum, its difference form, and the
// fused-multiply-add Two-Product). Exact barring overflow, and for the product barring underflow.

inline double two_sum(double a, double b, double& lo) {
    const double s = a + b;
    const double b_virtual = s - a;
    const double a_virtual = s - b_virtual;
    lo = (a - a_virtual) + (b - b_virtual);
    return s;
}

inline double two_diff(double a, double b, double& lo) {
    const double s = a - b;
    const double b_virtual = a - s;
    const double a_virtual = s + b_virtual;
    lo = (a - a_virtual) + (b_virtual - b);
    return s;
}

inline double two_product(double a, double b, double& lo) {
    const double p = a * b;
    lo = std::fma(a, b, -p);
    return p;
}

// ---- expansions --------------------------------------------------------------------------------
// A number represented exactly as the sum of up to N doubles that are nonoverlapping (the lowest
// set bit of each is above the highest set bit of the next smaller) and sorted by increasing
// magnitude, zeros removed. The largest component then carries the sign of the sum.

template <int N>
struct Expansion {
    double c[N];
    int n = 0;

    int sign() const { return n == 0 ? 0 : (c[n - 1] > 0.0 ? 1 : -1); }
};

// e += b (Shewchuk's Grow-Expansion, zeros eliminated), in place: the component written at step i
// goes to an index no greater than i. e must have room for one more component.
template <int N>
void grow(Expansion<N>& e, double b) {
    double q = b;
    int k = 0;
    for (int i = 0; i < e.n; ++i) {
        double lo;
        q = two_sum(q, e.c[i], lo);
        if (lo != 0.0) e.c[k++] = lo;
    }
    if (q != 0.0) {
        assert(k < N);
        e.c[k++] = q;
    }
    e.n = k;
}

// The exact difference a - b as an expansion.
Expansion<2> difference(double a, double b) {
    Expansion<2> e;
    double lo;
    const double hi = two_diff(a, b, lo);
    if (lo != 0.0) e.c[e.n++] = lo;
    if (hi != 0.0) e.c[e.n++] = hi;
    return e;
}

template <int M, int N>
Expansion<M + N> sum(const Expansion<M>& e, const Expansion<N>& f) {
    Expansion<M + N> h;
    for (int i = 0; i < e.n; ++i) h.c[i] = e.c[i];
    h.n = e.n;
    for (int i = 0; i < f.n; ++i) grow(h, f.c[i]);
    return h;
}

template <int N>
Expansion<N> negated(Expansion<N> e) {
    for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
    return e;
}

// e * b (Shewchuk's Scale-Expansion, zeros eliminated; Two-Sum in place of Fast-Two-Sum).
template <int M>
Expansion<2 * M> scaled(const Expansion<M>& e, double b) {
    Expansion<2 * M> h;
    if (e.n == 0 || b == 0.0) return h;
    double lo;
    double q = two_product(e.c[0], b, lo);
    if (lo != 0.0) h.c[h.n++] = lo;
    for (int i = 1; i < e.n; ++i) {
        double product_lo;
        const double product_hi = two_product(e.c[i], b, product_lo);
        double sum_lo;
        const double s = two_sum(q, product_lo, sum_lo);
        if (sum_lo != 0.0) h.c[h.n++] = sum_lo;
        q = two_sum(product_hi, s, lo);
        if (lo != 0.0) h.c[h.n++] = lo;
    }
    if (q != 0.0) h.c[h.n++] = q;
    return h;
}

// e * f, as the sum of e scaled by each component of f.
template <int M, int N>
Expansion<2 * M * N> product(const Expansion<M>& e, const Expansion<N>& f) {
    Expansion<2 * M * N> h;
    for (int j = 0; j < f.n; ++j) {
        const Expansion<2 * M> part = scaled(e, f.c[j]);
        for (int i = 0; i < part.n; ++i) grow(h, part.c[i]);
    }
    return h;
}

// ---- the exact evaluations ---------------------------------------------------------------------
// The differences of the inputs are taken exactly (two components each; one when the rounded
// difference is exact, which is the common case), then the determinant is expanded in full.

int orient2d_exact(const Point2d& a, const Point2d& b, const Point2d& c) {
    const Expansion<2> acx = difference(a.x, c.x), acy = difference(a.y, c.y);
    const Expansion<2> bcx = difference(b.x, c.x), bcy = difference(b.y, c.y);
    return sum(product(acx, bcy), negated(product(acy, bcx))).sign();
}

// The 2x2 minor p.x q.y - q.x p.y of exact differences.
Expansion<16> minor2x2(const Expansion<2>& px, const Expansion<2>& py, const Expansion<2>& qx,
                    const Expansion<2>& qy) {
    return sum(product(px, qy), negated(product(qx, py)));
}

int orient3d_exact(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const Expansion<2> adx = difference(a.x, d.x), ady = difference(a.y, d.y), adz = difference(a.z, d.z);
    const Expansion<2> bdx = difference(b.x, d.x), bdy = difference(b.y, d.y), bdz = difference(b.z, d.z);
    const Expansion<2> cdx = difference(c.x, d.x), cdy = difference(c.y, d.y), cdz = difference(c.z, d.z);
    // Expansion along the z column: adz (bc minor) + bdz (ca minor) + cdz (ab minor).
    const Expansion<64> a_term = product(minor2x2(bdx, bdy, cdx, cdy), adz);
    const Expansion<64> b_term = product(minor2x2(cdx, cdy, adx, ady), bdz);
    const Expansion<64> c_term = product(minor2x2(adx, ady, bdx, bdy), cdz);
    return sum(sum(a_term, b_term), c_term).sign();
}

// ---- the filters -------------------------------------------------------------------------------
// Shewchuk's bounds on the error of the straightforward evaluations below (including the rounding
// of the input differences), relative to the permanent: the same expression with every product
// replaced by its absolute value. When the computed determinant exceeds the bound its sign is
// exact. Half a unit in the last place of 1.
constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2.0;
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

inline int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace

int orient2d(const Point2d& a, const Point2d& b, const Point2d& c) {
    const double left = (a.x - c.x) * (b.y - c.y);
    const double right = (a.y - c.y) * (b.x - c.x);
    const double det = left - right;
    const double permanent = std::fabs(left) + std::fabs(right);
    if (std::fabs(det) > kOrient2dBound * permanent) return sign_of(det);
    // Both rounded products are 0, so each has a factor exactly 0 (no underflow in range).
    if (permanent == 0.0) return 0;
    return orient2d_exact(a, b, c);
}

int orient3d(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const double adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
    const double bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
    const double cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    const double cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
    if (std::fabs(det) > kOrient3dBound * permanent) return sign_of(det);
    // Every term of the permanent is 0, so each term of the determinant has a factor exactly 0.
    if (permanent == 0.0) return 0;
    return orient3d_exact(a, b, c, d);
}

}  // namespace nmesh
