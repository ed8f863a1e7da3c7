#include "nmesh/geometry/triangle_intersection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "nmesh/error.h"
#include "nmesh/geometry/exact_predicates.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

namespace {

using Face = std::array<std::uint32_t, 3>;

// ---- planar tests ------------------------------------------------------------------------------
// Points lying in one plane are compared in their projection on a coordinate plane on which the
// triangle at hand projects to a non-degenerate triangle: that projection maps the plane onto the
// coordinate plane one to one (an affine bijection), so it keeps every incidence.

// The projection dropping axis k (0: x, 1: y, 2: z).
Point2d project(const Vec3& v, int k) {
    switch (k) {
        case 0:
            return {double(v.y), double(v.z)};
        case 1:
            return {double(v.x), double(v.z)};
        default:
            return {double(v.x), double(v.y)};
    }
}

// The sign of the projection of abc with axis k dropped.
int projected_orientation(const Vec3& a, const Vec3& b, const Vec3& c, int k) {
    return orient2d(project(a, k), project(b, k), project(c, k));
}

// An axis whose dropping leaves abc a non-degenerate triangle, or -1 when abc is degenerate.
int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
    for (int k = 2; k >= 0; --k)
        if (projected_orientation(a, b, c, k) != 0) return k;
    return -1;
}

bool mixed_signs(int s1, int s2, int s3) { return (s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0); }

// Whether c, collinear with a and b, lies on the closed segment ab: within its bounding box.
bool on_segment_2d(const Point2d& a, const Point2d& b, const Point2d& c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
}

// Whether the closed segments pq and rs meet: they cross properly, or an endpoint of one lies on
// the other.
bool segments_meet_2d(const Point2d& p, const Point2d& q, const Point2d& r, const Point2d& s) {
    const int d1 = orient2d(r, s, p), d2 = orient2d(r, s, q);
    const int d3 = orient2d(p, q, r), d4 = orient2d(p, q, s);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && on_segment_2d(r, s, p)) || (d2 == 0 && on_segment_2d(r, s, q)) ||
           (d3 == 0 && on_segment_2d(p, q, r)) || (d4 == 0 && on_segment_2d(p, q, s));
}

// Whether p lies in the closed non-degenerate triangle abc, of either orientation: its three
// edge signs (the barycentric coordinates up to a common factor) do not disagree.
bool point_in_triangle_2d(const Point2d& p, const Point2d& a, const Point2d& b, const Point2d& c) {
    return !mixed_signs(orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p));
}

// Whether the segment pq, lying in the plane of the triangle abc, meets it: an endpoint inside, or
// the segment meeting an edge.
bool coplanar_segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int k = projection_axis(a, b, c);
    if (k < 0) return false;
    const Point2d p2 = project(p, k), q2 = project(q, k);
    const Point2d a2 = project(a, k), b2 = project(b, k), c2 = project(c, k);
    return point_in_triangle_2d(p2, a2, b2, c2) || point_in_triangle_2d(q2, a2, b2, c2) ||
           segments_meet_2d(p2, q2, a2, b2) || segments_meet_2d(p2, q2, b2, c2) || segments_meet_2d(p2, q2, c2, a2);
}

// Two triangles P and Q lying in one plane, projected on a coordinate plane on which P (hence Q)
// is non-degenerate, with the sides of each one's corners relative to the other's edge lines:
// p_side[m][k] = orient2d(Q[k], Q[k+1], P[m]) and q_side[m][k] = orient2d(P[k], P[k+1], Q[m]).
// The edge tests read these 18 signs only.
//
// An edge test reports an end of the edge inside the other triangle, or a proper crossing of one
// of its edges (at a point interior to both). Any other contact between an edge and the other
// triangle puts a corner of that triangle on the edge: the test of an edge ending at that corner,
// run by the caller, sees the corner inside.
class CoplanarTriangles {
public:
    CoplanarTriangles(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1, const Vec3& q2,
                      int axis) {
        const Point2d p[3] = {project(p0, axis), project(p1, axis), project(p2, axis)};
        const Point2d q[3] = {project(q0, axis), project(q1, axis), project(q2, axis)};
        for (int m = 0; m < 3; ++m)
            for (int k = 0; k < 3; ++k) {
                p_side_[m][k] = orient2d(q[k], q[(k + 1) % 3], p[m]);
                q_side_[m][k] = orient2d(p[k], p[(k + 1) % 3], q[m]);
            }
    }

    // The edge from corner i to corner i + 1 of P against Q, and the converse.
    bool p_edge_meets_q(int i) const { return edge_meets(p_side_, q_side_, i); }
    bool q_edge_meets_p(int i) const { return edge_meets(q_side_, p_side_, i); }

private:
    // Edge i of a triangle e against a triangle t, given e_side[m][k], the side of e's corner m
    // relative to t's edge k, and t_side[m][k], the side of t's corner m relative to e's edge k.
    static bool edge_meets(const int (&e_side)[3][3], const int (&t_side)[3][3], int i) {
        const int j = (i + 1) % 3;
        if (!mixed_signs(e_side[i][0], e_side[i][1], e_side[i][2]) ||
            !mixed_signs(e_side[j][0], e_side[j][1], e_side[j][2]))
            return true;
        for (int k = 0; k < 3; ++k) {
            // The edge's ends strictly on both sides of t's edge line k, and t's edge k's ends
            // strictly on both sides of the edge's line.
            if (e_side[i][k] * e_side[j][k] < 0 && t_side[k][i] * t_side[(k + 1) % 3][i] < 0) return true;
        }
        return false;
    }

    int p_side_[3][3], q_side_[3][3];
};

// ---- segment and triangle ----------------------------------------------------------------------

// Whether the closed segment pq meets the closed triangle abc, given sp = orient3d(a, b, c, p) and
// sq = orient3d(a, b, c, q).
bool segment_meets_triangle(const Vec3& p, const Vec3& q, int sp, int sq, const Vec3& a, const Vec3& b, const Vec3& c) {
    if (sp == sq) {
        if (sp != 0) return false;  // both strictly on one side of the plane
        return coplanar_segment_meets_triangle(p, q, a, b, c);
    }
    // The segment meets the plane in exactly one point, and the line pq is not parallel to it.
    // That point is in the triangle iff the line passes on no two opposite sides of its edges:
    // the sign of orient3d(p, q, a, b) is that of the point's turn with the edge ab in the plane,
    // times a factor common to the three edges (moving p and q along their line does not change
    // the determinant).
    return !mixed_signs(orient3d(p, q, a, b), orient3d(p, q, b, c), orient3d(p, q, c, a));
}

// Whether some edge of the triangle abc meets the triangle def, given the sides sa, sb, sc of a,
// b, c with respect to the plane of def.
bool edges_meet_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int sa, int sb, int sc, const Vec3& d,
                         const Vec3& e, const Vec3& f) {
    return segment_meets_triangle(a, b, sa, sb, d, e, f) || segment_meets_triangle(b, c, sb, sc, d, e, f) ||
           segment_meets_triangle(c, a, sc, sa, d, e, f);
}

// ---- faces of a mesh ---------------------------------------------------------------------------

// Whether the triangles pqa and pqb, sharing the edge pq, overlap off it. Out of one plane they
// meet only on the line of the two planes, where each is just the edge. In one plane each lies
// in the closed half-plane of its opposite vertex: on opposite sides these meet only on the line
// pq; on the same side both triangles contain points near the middle of the edge on that side.
bool folded(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b) {
    if (orient3d(p, q, a, b) != 0) return false;
    const int k = projection_axis(p, q, a);
    return k >= 0 && projected_orientation(p, q, a, k) == projected_orientation(p, q, b, k);
}

bool face_degenerate(const Vec3* positions, const Face& t) {
    return t[0] == t[1] || t[1] == t[2] || t[2] == t[0] ||
           triangle_degenerate(positions[t[0]], positions[t[1]], positions[t[2]]);
}

// faces_intersect for faces known to be non-degenerate.
bool nondegenerate_faces_intersect(const Vec3* positions, const Face& t, const Face& u) {
    bool t_shared[3] = {false, false, false}, u_shared[3] = {false, false, false};
    int shared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (t[i] == u[j]) {
                t_shared[i] = u_shared[j] = true;
                ++shared;
            }
    const auto at = [positions](std::uint32_t v) -> const Vec3& { return positions[v]; };
    switch (shared) {
        case 0:
            return triangles_intersect_exact(at(t[0]), at(t[1]), at(t[2]), at(u[0]), at(u[1]), at(u[2]));
        case 1: {
            // t = (v, a, b), u = (v, c, d). Beyond v iff ab meets u or cd meets t. If x != v is
            // common, the ray from v through x leaves t at a point y of ab (t is the union of the
            // segments from v to the points of ab) and leaves u at a point z of cd; both [v, y]
            // and [v, z] lie on the ray and contain x, so the nearer of y and z lies in both
            // triangles. Conversely a common point on ab or cd is not v, which neither contains.
            const int i = t_shared[0] ? 0 : (t_shared[1] ? 1 : 2);
            const int j = u_shared[0] ? 0 : (u_shared[1] ? 1 : 2);
            const Vec3 &v = at(t[i]), &a = at(t[(i + 1) % 3]), &b = at(t[(i + 2) % 3]);
            const Vec3 &c = at(u[(j + 1) % 3]), &d = at(u[(j + 2) % 3]);
            const int sa = orient3d(v, c, d, a), sb = orient3d(v, c, d, b);
            if (sa == 0 && sb == 0) {  // t lies in the plane of u
                // The edge tests of ab and cd cover each other's contacts at a corner (v lies on
                // neither segment).
                const CoplanarTriangles pair(v, a, b, v, c, d, projection_axis(v, a, b));
                return pair.p_edge_meets_q(1) || pair.q_edge_meets_p(1);
            }
            // Not coplanar: c and d are not both in the plane of t either.
            return segment_meets_triangle(a, b, sa, sb, v, c, d) ||
                   segment_meets_triangle(c, d, orient3d(v, a, b, c), orient3d(v, a, b, d), v, a, b);
        }
        case 2: {  // t = (p, q, a), u = (p, q, b)
            const int i = !t_shared[0] ? 0 : (!t_shared[1] ? 1 : 2);
            const int j = !u_shared[0] ? 0 : (!u_shared[1] ? 1 : 2);
            return folded(at(t[(i + 1) % 3]), at(t[(i + 2) % 3]), at(t[i]), at(u[j]));
        }
        default:
            return true;  // the same face twice
    }
}

// ---- the broad phase ---------------------------------------------------------------------------

// A face's bounding box and the range of grid cells it covers.
struct FaceBox {
    float lo[3], hi[3];
    int cell_lo[3], cell_hi[3];
};

bool boxes_overlap(const FaceBox& a, const FaceBox& b) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] > b.hi[k] || b.lo[k] > a.hi[k]) return false;
    return true;
}

// The intersecting pairs of a mesh's faces, face by face.
//
// The non-degenerate faces are binned by their bounding boxes into a uniform grid of cubic cells
// as wide as the mean largest box side (coarser if that would make more than about 8 cells per
// face), counting-sorted so that each cell lists its faces in increasing order. Each face s then
// looks at the faces t > s in the cells its box covers. Closed boxes that overlap share the cell
// that holds the lower corner of their overlap: the cell of a coordinate is monotonic in it, so
// that cell is, axis by axis, the larger of the two boxes' first cells. A pair is tested only in
// that cell, hence once. The faces' searches are independent of each other (several threads may
// search at once).
class IntersectingPairs {
public:
    explicit IntersectingPairs(const IndexedMesh& mesh);
    // The number of faces tested (the non-degenerate ones with finite corners).
    std::size_t size() const { return faces_.size(); }
    // The faces t > s (s = the i-th face tested) that intersect s, increasing, into `found`.
    void partners(std::size_t i, std::vector<std::uint32_t>& found) const;
    // The mesh's index of the i-th face tested.
    std::uint32_t face(std::size_t i) const { return faces_[i]; }

private:
    const IndexedMesh& mesh_;
    std::vector<std::uint32_t> faces_;  // the faces tested, increasing
    std::vector<FaceBox> boxes_;
    int dim_[3] = {0, 0, 0};
    std::vector<std::size_t> start_;
    std::vector<std::uint32_t> entries_;
    std::size_t cell_id(int x, int y, int z) const {
        return (std::size_t(z) * std::size_t(dim_[1]) + std::size_t(y)) * std::size_t(dim_[0]) + std::size_t(x);
    }
};

IntersectingPairs::IntersectingPairs(const IndexedMesh& mesh) : mesh_(mesh) {
    const std::size_t face_count = mesh.triangles.size();
    const std::size_t vertex_count = mesh.positions.size();
    if (face_count > std::size_t(UINT32_MAX)) throw InputError("self_intersecting_pairs: more than 2^32 - 1 triangles");
    const Vec3* positions = mesh.positions.data();

    std::vector<std::uint32_t>& faces = faces_;
    faces.reserve(face_count);
    for (std::size_t f = 0; f < face_count; ++f) {
        const Face& t = mesh.triangles[f];
        for (std::uint32_t v : t)
            if (v >= vertex_count)
                throw InputError("self_intersecting_pairs: triangle " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + " of " + std::to_string(vertex_count));
        bool finite = true;
        for (std::uint32_t v : t)
            finite = finite && std::isfinite(positions[v].x) && std::isfinite(positions[v].y) &&
                     std::isfinite(positions[v].z);
        if (finite && !face_degenerate(positions, t)) faces.push_back(std::uint32_t(f));
    }
    const std::size_t n = faces.size();
    if (n < 2) {
        faces.clear();  // nothing to pair
        return;
    }

    std::vector<FaceBox>& boxes = boxes_;
    boxes.resize(n);
    double lower[3], upper[3], side_sum = 0.0;
    for (int k = 0; k < 3; ++k) {
        lower[k] = HUGE_VAL;
        upper[k] = -HUGE_VAL;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Face& t = mesh.triangles[faces[i]];
        FaceBox& b = boxes[i];
        double side = 0.0;
        for (int k = 0; k < 3; ++k) {
            const float p = positions[t[0]][k], q = positions[t[1]][k], r = positions[t[2]][k];
            b.lo[k] = std::min({p, q, r});
            b.hi[k] = std::max({p, q, r});
            lower[k] = std::min(lower[k], double(b.lo[k]));
            upper[k] = std::max(upper[k], double(b.hi[k]));
            side = std::max(side, double(b.hi[k]) - double(b.lo[k]));
        }
        side_sum += side;
    }

    // A non-degenerate face has a box of positive size, so the cell width is positive.
    double width = side_sum / double(n);
    const double max_cells = std::min(8.0 * double(n) + 64.0, 1073741824.0);
    double dims[3];
    for (;;) {
        double cells = 1.0;
        for (int k = 0; k < 3; ++k) {
            dims[k] = std::floor((upper[k] - lower[k]) / width) + 1.0;
            cells *= dims[k];
        }
        if (cells <= max_cells) break;
        width *= std::max(1.01, std::cbrt(cells / max_cells));
    }
    int* const dim = dim_;
    for (int k = 0; k < 3; ++k) dim[k] = int(dims[k]);
    const double inverse_width = 1.0 / width;
    const auto cell_of = [&](float x, int k) {
        const double c = std::floor((double(x) - lower[k]) * inverse_width);
        return int(std::clamp(c, 0.0, double(dim[k] - 1)));
    };

    // Counting sort of (cell, face) entries by cell, faces increasing within a cell.
    const std::size_t cell_count = std::size_t(dim[0]) * std::size_t(dim[1]) * std::size_t(dim[2]);
    std::vector<std::size_t>& start = start_;
    start.assign(cell_count + 1, 0);
    for (FaceBox& b : boxes) {
        for (int k = 0; k < 3; ++k) {
            b.cell_lo[k] = cell_of(b.lo[k], k);
            b.cell_hi[k] = cell_of(b.hi[k], k);
        }
        for (int z = b.cell_lo[2]; z <= b.cell_hi[2]; ++z)
            for (int y = b.cell_lo[1]; y <= b.cell_hi[1]; ++y)
                for (int x = b.cell_lo[0]; x <= b.cell_hi[0]; ++x) ++start[cell_id(x, y, z) + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<std::uint32_t>& entries = entries_;
    entries.resize(start.back());
    {
        std::vector<std::size_t> next(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < n; ++i) {
            const FaceBox& b = boxes[i];
            for (int z = b.cell_lo[2]; z <= b.cell_hi[2]; ++z)
                for (int y = b.cell_lo[1]; y <= b.cell_hi[1]; ++y)
                    for (int x = b.cell_lo[0]; x <= b.cell_hi[0]; ++x)
                        entries[next[cell_id(x, y, z)]++] = std::uint32_t(i);
        }
    }
}

void IntersectingPairs::partners(std::size_t i, std::vector<std::uint32_t>& found) const {
    const std::uint32_t* const listed = entries_.data();
    const FaceBox& a = boxes_[i];
    const Face& t = mesh_.triangles[faces_[i]];
    found.clear();
    for (int z = a.cell_lo[2]; z <= a.cell_hi[2]; ++z)
        for (int y = a.cell_lo[1]; y <= a.cell_hi[1]; ++y)
            for (int x = a.cell_lo[0]; x <= a.cell_hi[0]; ++x) {
                const std::size_t c = cell_id(x, y, z);
                const std::uint32_t* const end = listed + start_[c + 1];
                for (const std::uint32_t* e = std::upper_bound(listed + start_[c], end, std::uint32_t(i)); e != end; ++e) {
                    const FaceBox& b = boxes_[*e];
                    if (std::max(a.cell_lo[0], b.cell_lo[0]) != x || std::max(a.cell_lo[1], b.cell_lo[1]) != y ||
                        std::max(a.cell_lo[2], b.cell_lo[2]) != z)
                        continue;
                    if (!boxes_overlap(a, b)) continue;
                    if (nondegenerate_faces_intersect(mesh_.positions.data(), t, mesh_.triangles[faces_[*e]]))
                        found.push_back(*e);
                }
            }
    std::sort(found.begin(), found.end());
}

}  // namespace

bool triangle_degenerate(const Vec3& a, const Vec3& b, const Vec3& c) { return projection_axis(a, b, c) < 0; }

bool segment_intersects_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    return segment_meets_triangle(p, q, orient3d(a, b, c, p), orient3d(a, b, c, q), a, b, c);
}

bool triangles_intersect_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                               const Vec3& f) {
    const int sd = orient3d(a, b, c, d), se = orient3d(a, b, c, e), sf = orient3d(a, b, c, f);
    if (sd == se && se == sf && sd != 0) return false;  // def strictly on one side of abc's plane
    // In one plane, either the boundaries meet or one triangle contains the other (then its
    // edges lie in the other): some edge of one meets the other.
    if (sd == 0 && se == 0 && sf == 0) {
        const int axis = projection_axis(a, b, c);
        if (axis < 0) return false;
        const CoplanarTriangles pair(a, b, c, d, e, f, axis);
        for (int i = 0; i < 3; ++i)
            if (pair.p_edge_meets_q(i) || pair.q_edge_meets_p(i)) return true;
        return false;
    }
    const int sa = orient3d(d, e, f, a), sb = orient3d(d, e, f, b), sc = orient3d(d, e, f, c);
    if (sa == sb && sb == sc && sa != 0) return false;
    // Out of one plane, the common part lies on the line of the two planes, where each triangle
    // is a segment with its ends on its edges; the overlap of the two segments, if any, has an end
    // that is an end of one of them, so an edge of one triangle meets the other.
    return edges_meet_triangle(d, e, f, sd, se, sf, a, b, c) || edges_meet_triangle(a, b, c, sa, sb, sc, d, e, f);
}

bool faces_intersect(const Vec3* positions, std::array<std::uint32_t, 3> t, std::array<std::uint32_t, 3> u) {
    if (face_degenerate(positions, t) || face_degenerate(positions, u)) return false;
    return nondegenerate_faces_intersect(positions, t, u);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs(const IndexedMesh& mesh,
                                                                             std::size_t max_pairs) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    if (max_pairs == 0) return pairs;
    const IntersectingPairs search(mesh);
    std::vector<std::uint32_t> found;
    for (std::size_t i = 0; i < search.size(); ++i) {
        search.partners(i, found);
        for (const std::uint32_t j : found) {
            pairs.emplace_back(search.face(i), search.face(j));
            if (pairs.size() >= max_pairs) return pairs;
        }
    }
    return pairs;
}

std::size_t count_self_intersections(const IndexedMesh& mesh, std::uint32_t threads) {
    const IntersectingPairs search(mesh);
    // Counts per chunk of faces, added up in chunk order (integers: any order gives the same sum).
    constexpr std::size_t kChunk = 512;
    std::vector<std::size_t> counts((search.size() + kChunk - 1) / kChunk, 0);
    for_chunks(search.size(), kChunk, threads, [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t> found;
        std::size_t count = 0;
        for (std::size_t i = begin; i < end; ++i) {
            search.partners(i, found);
            count += found.size();
        }
        counts[begin / kChunk] = count;
    });
    std::size_t total = 0;
    for (const std::size_t c : counts) total += c;
    return total;
}

}  // namespace nmesh
