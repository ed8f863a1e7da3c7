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

inline int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

// ---- expansions --------------------------------------------------------------------------------
// A number represented exactly as the sum of the doubles e[0..n): nonoverlapping (the lowest set
// bit of each is above the highest set bit of the next smaller) and sorted by increasing
// magnitude, zeros removed. The largest component then carries the sign of the sum. Each
// operation writes its result to a caller's array of sufficient size and returns its length.

int sign_of_expansion(const double* e, int n) { return n == 0 ? 0 : (e[n - 1] > 0.0 ? 1 : -1); }

// e += b (Shewchuk's Grow-Expansion, zeros eliminated), in place: the component written at step i
// goes to an index no greater than i. e must have room for n + 1 components.
int grow(double* e, int n, double b) {
    double q = b;
    int k = 0;
    for (int i = 0; i < n; ++i) {
        double lo;
        q = two_sum(q, e[i], lo);
        if (lo != 0.0) e[k++] = lo;
    }
    if (q != 0.0) e[k++] = q;
    return k;
}

// h = e + f (Shewchuk's Expansion-Sum: f's components grown into e in turn); h has room for
// en + fn components and may not overlap f.
int add(const double* e, int en, const double* f, int fn, double* h) {
    for (int i = 0; i < en; ++i) h[i] = e[i];
    int n = en;
    for (int i = 0; i < fn; ++i) n = grow(h, n, f[i]);
    return n;
}

// h = e * b (Shewchuk's Scale-Expansion, zeros eliminated; Two-Sum in place of Fast-Two-Sum); h
// has room for 2 en components.
int scale(const double* e, int en, double b, double* h) {
    if (en == 0 || b == 0.0) return 0;
    int n = 0;
    double lo;
    double q = two_product(e[0], b, lo);
    if (lo != 0.0) h[n++] = lo;
    for (int i = 1; i < en; ++i) {
        double product_lo;
        const double product_hi = two_product(e[i], b, product_lo);
        double sum_lo;
        const double s = two_sum(q, product_lo, sum_lo);
        if (sum_lo != 0.0) h[n++] = sum_lo;
        q = two_sum(product_hi, s, lo);
        if (lo != 0.0) h[n++] = lo;
    }
    if (q != 0.0) h[n++] = q;
    return n;
}

// h = e * f for e of at most 16 components and f of at most two, as e scaled by each; h has room
// for 4 en components.
int multiply(const double* e, int en, const double* f, int fn, double* h) {
    assert(fn <= 2 && en <= 16);
    if (fn == 1) return scale(e, en, f[0], h);
    int n = 0;
    for (int j = 0; j < fn; ++j) {
        double part[2 * 16];
        const int pn = scale(e, en, f[j], part);
        for (int i = 0; i < pn; ++i) n = grow(h, n, part[i]);
    }
    return n;
}

// The exact difference a - b, of one or two components (one when the rounded difference is exact,
// the common case; none when a == b).
struct Difference {
    double c[2];
    int n = 0;
};

Difference difference(double a, double b) {
    Difference d;
    double lo;
    const double hi = two_diff(a, b, lo);
    if (lo != 0.0) d.c[d.n++] = lo;
    if (hi != 0.0) d.c[d.n++] = hi;
    return d;
}

// ---- the exact evaluations ---------------------------------------------------------------------
// The differences of the inputs are taken exactly, then the determinant is expanded in full.

// h = p.x q.y - q.x p.y, of at most 16 components.
int minor2x2(const Difference& px, const Difference& py, const Difference& qx, const Difference& qy, double* h) {
    double left[8], right[8];
    const int ln = multiply(px.c, px.n, qy.c, qy.n, left);
    int rn = multiply(qx.c, qx.n, py.c, py.n, right);
    for (int i = 0; i < rn; ++i) right[i] = -right[i];
    return add(left, ln, right, rn, h);
}

// The plain evaluations again, each rounding error now computed by an error-free transformation:
// when every one is zero, the plain value is the exact determinant and its sign is returned;
// otherwise 2 (undecided). Cheap, with no data-dependent loops, and decisive for inputs of few
// significant bits such as integer or grid coordinates, where exact zeros are common.

int plain_orient2d_if_exact(const Point2d& a, const Point2d& b, const Point2d& c) {
    double e[6];
    const double acx = two_diff(a.x, c.x, e[0]), acy = two_diff(a.y, c.y, e[1]);
    const double bcx = two_diff(b.x, c.x, e[2]), bcy = two_diff(b.y, c.y, e[3]);
    const double left = two_product(acx, bcy, e[4]), right = two_product(acy, bcx, e[5]);
    for (double x : e)
        if (x != 0.0) return 2;
    // The last rounding keeps the sign of the exact difference.
    return sign_of(left - right);
}

int plain_orient3d_if_exact(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    double e[9];
    const double adx = two_diff(a.x, d.x, e[0]), ady = two_diff(a.y, d.y, e[1]), adz = two_diff(a.z, d.z, e[2]);
    const double bdx = two_diff(b.x, d.x, e[3]), bdy = two_diff(b.y, d.y, e[4]), bdz = two_diff(b.z, d.z, e[5]);
    const double cdx = two_diff(c.x, d.x, e[6]), cdy = two_diff(c.y, d.y, e[7]), cdz = two_diff(c.z, d.z, e[8]);
    for (double x : e)
        if (x != 0.0) return 2;
    double r[13];
    const double m1 = two_diff(two_product(bdx, cdy, r[0]), two_product(cdx, bdy, r[1]), r[2]);
    const double m2 = two_diff(two_product(cdx, ady, r[3]), two_product(adx, cdy, r[4]), r[5]);
    const double m3 = two_diff(two_product(adx, bdy, r[6]), two_product(bdx, ady, r[7]), r[8]);
    const double t1 = two_product(adz, m1, r[9]), t2 = two_product(bdz, m2, r[10]), t3 = two_product(cdz, m3, r[11]);
    const double t12 = two_sum(t1, t2, r[12]);
    for (double x : r)
        if (x != 0.0) return 2;
    // The last rounding keeps the sign of the exact sum.
    return sign_of(t12 + t3);
}

int orient2d_exact(const Point2d& a, const Point2d& b, const Point2d& c) {
    double det[16];
    const int n = minor2x2(difference(a.x, c.x), difference(a.y, c.y), difference(b.x, c.x), difference(b.y, c.y), det);
    return sign_of_expansion(det, n);
}

int orient3d_exact(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
    const Difference adx = difference(a.x, d.x), ady = difference(a.y, d.y), adz = difference(a.z, d.z);
    const Difference bdx = difference(b.x, d.x), bdy = difference(b.y, d.y), bdz = difference(b.z, d.z);
    const Difference cdx = difference(c.x, d.x), cdy = difference(c.y, d.y), cdz = difference(c.z, d.z);
    // Expansion along the z column: adz (bc minor) + bdz (ca minor) + cdz (ab minor); each term
    // has at most 64 components.
    double minor[16], term[64], det[192];
    int n = minor2x2(bdx, bdy, cdx, cdy, minor);
    n = multiply(minor, n, adz.c, adz.n, det);
    int mn = minor2x2(cdx, cdy, adx, ady, minor);
    int tn = multiply(minor, mn, bdz.c, bdz.n, term);
    for (int i = 0; i < tn; ++i) n = grow(det, n, term[i]);
    mn = minor2x2(adx, ady, bdx, bdy, minor);
    tn = multiply(minor, mn, cdz.c, cdz.n, term);
    for (int i = 0; i < tn; ++i) n = grow(det, n, term[i]);
    return sign_of_expansion(det, n);
}

// ---- the filters -------------------------------------------------------------------------------
// Shewchuk's bounds on the error of the straightforward evaluations below (including the rounding
// of the input differences), relative to the permanent: the same expression with every product
// replaced by its absolute value. When the computed determinant exceeds the bound its sign is
// exact. kEpsilon is half a unit in the last place of 1.
constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2.0;
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

}  // namespace

int orient2d(const Point2d& a, const Point2d& b, const Point2d& c) {
    const double left = (a.x - c.x) * (b.y - c.y);
    const double right = (a.y - c.y) * (b.x - c.x);
    const double det = left - right;
    const double permanent = std::fabs(left) + std::fabs(right);
    if (std::fabs(det) > kOrient2dBound * permanent) return sign_of(det);
    // Both rounded products are 0, so each has a factor exactly 0 (no underflow in range).
    if (permanent == 0.0) return 0;
    const int plain = plain_orient2d_if_exact(a, b, c);
    return plain != 2 ? plain : orient2d_exact(a, b, c);
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
    const int plain = plain_orient3d_if_exact(a, b, c, d);
    return plain != 2 ? plain : orient3d_exact(a, b, c, d);
}

}  // namespace nmesh
