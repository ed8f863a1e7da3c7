#include "nmesh/mesh/orientation.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "nmesh/mesh/mesh_pieces.h"
#include "nmesh/util/parallel.h"

namespace nmesh {
namespace {

struct Point3 {
    double x, y, z;
};
Point3 to_double(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
Point3 minus(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point3 cross3(const Point3& a, const Point3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot3(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// +1 or -1 when the ray from p along +x crosses the triangle abc (the sign of its normal's x
// component), 0 when it misses. A ray exactly through an edge or a vertex counts each triangle
// there; the query points (off face centroids) practically never lie on one.
int crossing(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
    // Orientation of p's projection against each projected edge in the (y, z) plane.
    const auto side = [&](const Point3& u, const Point3& v) {
        return (v.y - u.y) * (p.z - u.z) - (v.z - u.z) * (p.y - u.y);
    };
    const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    const bool positive = s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0 && (s0 > 0.0 || s1 > 0.0 || s2 > 0.0);
    const bool negative = s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0 && (s0 < 0.0 || s1 < 0.0 || s2 < 0.0);
    if (!positive && !negative) return 0;
    // Where the ray meets the triangle's plane: beyond p, or no crossing.
    const Point3 n = cross3(minus(b, a), minus(c, a));
    if (n.x == 0.0) return 0;
    const double t = dot3(n, minus(a, p)) / n.x;
    if (!(t > 0.0)) return 0;
    return n.x > 0.0 ? 1 : -1;
}

// Whether face i points inward (inward_face_flags).
std::uint8_t points_inward(const IndexedMesh& mesh, const TriangleBvh& bvh, std::size_t i) {
    const auto& t = mesh.triangles[i];
    const Point3 a = to_double(mesh.positions[t[0]]), b = to_double(mesh.positions[t[1]]),
                 c = to_double(mesh.positions[t[2]]);
    const Point3 n = cross3(minus(b, a), minus(c, a));
    const double len = std::sqrt(dot3(n, n));
    if (!(len > 0.0)) return 0;
    const double edge = std::sqrt(
        std::max({dot3(minus(b, a), minus(b, a)), dot3(minus(c, b), minus(c, b)), dot3(minus(a, c), minus(a, c))}));
    const double off = 1e-3 * edge / len;
    const Point3 p{(a.x + b.x + c.x) / 3.0 + n.x * off, (a.y + b.y + c.y) / 3.0 + n.y * off,
                   (a.z + b.z + c.z) / 3.0 + n.z * off};
    // The query point rounded to float, so that the hierarchy's float boxes and the crossing
    // test see the same point.
    const Vec3 origin(float(p.x), float(p.y), float(p.z));
    const Point3 q = to_double(origin);
    int winding = 0;
    bvh.for_each_on_ray_x(origin, [&](std::uint32_t f) {
        const auto& u = mesh.triangles[f];
        winding += crossing(q, to_double(mesh.positions[u[0]]), to_double(mesh.positions[u[1]]),
                            to_double(mesh.positions[u[2]]));
    });
    return std::uint8_t(winding != 0);
}

}  // namespace

double signed_volume(const IndexedMesh& mesh) {
    double six_v = 0.0;
    for (const auto& t : mesh.triangles) {
        const Point3 a = to_double(mesh.positions[t[0]]), b = to_double(mesh.positions[t[1]]),
                     c = to_double(mesh.positions[t[2]]);
        six_v += dot3(a, cross3(b, c));
    }
    return six_v / 6.0;
}

bool orient_outward(IndexedMesh& mesh) {
    if (!(signed_volume(mesh) < 0.0)) return false;
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return true;
}

std::vector<std::uint8_t> inward_face_flags(const IndexedMesh& mesh, const TriangleBvh& bvh, std::uint32_t threads) {
    std::vector<std::uint8_t> inward(mesh.triangles.size(), 0);
    for_chunks(mesh.triangles.size(), 1024, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) inward[i] = points_inward(mesh, bvh, i);
    });
    return inward;
}

std::size_t inward_faces(const IndexedMesh& mesh, const TriangleBvh& bvh, std::uint32_t threads) {
    const std::vector<std::uint8_t> inward = inward_face_flags(mesh, bvh, threads);
    return std::size_t(std::count(inward.begin(), inward.end(), std::uint8_t(1)));
}

std::size_t largest_patch(const IndexedMesh& mesh, const std::vector<std::uint8_t>& flagged) {
    IndexedMesh patches;
    patches.positions = mesh.positions;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        if (flagged[t]) patches.triangles.push_back(mesh.triangles[t]);
    std::size_t largest = 0;
    for (const MeshPiece& piece : split_pieces(patches)) largest = std::max(largest, piece.mesh.triangles.size());
    return largest;
}

}  // namespace nmesh
