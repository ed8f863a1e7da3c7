// The finishing stage (nmesh/finish.h). Choice beyond the paper, which stops when the mesh has its
// target size: the learnt mesh is regularised and its folds and self-intersections repaired;
// Parameters::finish = false switches the stage off and gives the paper's plain algorithm.
#include "nmesh/util/math_constants.h"
#include "nmesh/finish/finish.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "nmesh/metrics.h"

namespace nmesh {
namespace {

// The relaxation pulls a vertex towards the cloud by at most this share of its mean edge length
// per round: where the surface is thinner than a triangle, a larger pull could cross to the
// other side.
constexpr float kPullLimit = 0.25f;
// Pull-back iterations after a successful repair.
constexpr int kRefitIterations = 3;

// ---- small helpers ----------------------------------------------------------------------------------

std::vector<Vertex> alive_vertices(const Mesh& mesh) {
    std::vector<Vertex> v;
    v.reserve(mesh.n_vertices());
    for (std::uint32_t i = 0; i < mesh.vertex_capacity(); ++i)
        if (!mesh.is_removed(Vertex(i))) v.push_back(Vertex(i));
    return v;
}

std::vector<Face> alive_faces(const Mesh& mesh) {
    std::vector<Face> f;
    f.reserve(mesh.n_faces());
    for (std::uint32_t i = 0; i < mesh.face_capacity(); ++i)
        if (!mesh.is_removed(Face(i))) f.push_back(Face(i));
    return f;
}

// A nearest-point index over the positions of `verts`: index i names verts[i].
std::unique_ptr<PointGrid> position_index(const Mesh& mesh, const std::vector<Vertex>& verts) {
    std::vector<Vec3> pos(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) pos[i] = mesh.position(verts[i]);
    return std::make_unique<PointGrid>(pos);
}

std::array<Vertex, 3> corners(const Mesh& mesh, Face f) {
    const Halfedge h = mesh.halfedge(f);
    return {mesh.from(h), mesh.to(h), mesh.to(mesh.next(h))};
}

// Twice the area of a face, along its normal.
Vec3 area_vector(const Mesh& mesh, Face f) {
    const auto c = corners(mesh, f);
    const Vec3& p = mesh.position(c[0]);
    return cross(mesh.position(c[1]) - p, mesh.position(c[2]) - p);
}

float length(const Mesh& mesh, Halfedge h) { return distance(mesh.position(mesh.from(h)), mesh.position(mesh.to(h))); }

float mean_edge_length(const Mesh& mesh) {
    double sum = 0.0;
    std::uint32_t n = 0;
    for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e) {
        if (mesh.is_removed(Edge(e))) continue;
        sum += length(mesh, Mesh::halfedge(Edge(e), 0));
        ++n;
    }
    return n ? float(sum / n) : 0.0f;
}

// cot of the angle at c of the triangle (a, b, c); +-infinity for a degenerate triangle (the sign
// of the cosine: an angle of 0 or of 180 degrees).
float cot_at(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = a - c, v = b - c;
    const float d = dot(u, v);
    const float s = norm(cross(u, v));
    if (s == 0.0f) return d >= 0.0f ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
    return d / s;
}

bool edge_folded(const Mesh& mesh, Halfedge h, float cos_limit) {
    const Vec3 n0 = area_vector(mesh, mesh.face(h)), n1 = area_vector(mesh, mesh.face(Mesh::twin(h)));
    const float l0 = squared_norm(n0), l1 = squared_norm(n1);
    if (l0 == 0.0f || l1 == 0.0f) return true;  // a degenerate triangle
    return dot(n0, n1) < cos_limit * std::sqrt(l0) * std::sqrt(l1);
}

// Where tangential relaxation takes a vertex: towards the area-weighted centroid of its triangles'
// centroids, without the normal component of the move, then (with a cloud) pulled towards it.
Vec3 relaxed_position(const Mesh& mesh, Vertex v, const CloudSurface* cloud, float mean_edge) {
    const Vec3 p = mesh.position(v);
    Vec3 centroid, normal;
    float area = 0.0f, ring_length = 0.0f;
    std::uint32_t valence = 0;
    mesh.for_each_outgoing(v, [&](Halfedge h) {
        const Vec3& q1 = mesh.position(mesh.to(h));
        const Vec3& q2 = mesh.position(mesh.to(mesh.next(h)));
        const Vec3 x = cross(q1 - p, q2 - p);  // twice the area, along the normal
        const float a = norm(x);
        centroid += (p + q1 + q2) * (a / 3.0f);
        area += a;
        normal += x;
        ring_length += distance(p, q1);
        ++valence;
    });
    if (!(area > 0.0f)) return p;
    const Vec3 n = normalized(normal);
    const Vec3 d = centroid * (1.0f / area) - p;
    const Vec3 q = p + (d - n * dot(d, n));
    if (!cloud) return q;
    const float edge = ring_length / float(valence);
    // A move that would take the vertex more than a (mesh-wide mean) edge length away from the
    // cloud, and farther than it was, is no slide along the scanned surface (it happens over holes
    // in the scan, where the big triangles spanning the hole would draw the vertices around it
    // inwards): the vertex stays.
    const NearestPoint near = cloud->index().find_nearest(q);
    const float d2 = near.squared_distance;
    if (d2 > mean_edge * mean_edge && d2 > cloud->index().nearest_squared_distance(p)) return p;
    return cloud->pull(q, n, kPullLimit * edge, edge, near);
}

// The closest point of the triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    const Vec3 bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) return a;  // a degenerate triangle
    return a + ab * (vb / sum) + ac * (vc / sum);
}

// Distance from x to the triangles around v (an upper bound of its distance to the surface, and
// close to it when v is the vertex nearest to x).
float distance_to_ring(const Mesh& mesh, Vertex v, const Vec3& x) {
    float best = std::numeric_limits<float>::infinity();
    const Vec3& a = mesh.position(v);
    mesh.for_each_outgoing(v, [&](Halfedge h) {
        const Vec3 y = closest_on_triangle(x, a, mesh.position(mesh.to(h)), mesh.position(mesh.to(mesh.next(h))));
        best = std::min(best, squared_distance(x, y));
    });
    return std::sqrt(best);
}

// The Hausdorff distance between a mesh and the cloud, estimated from both sides: each cloud point
// measured against the triangles around its nearest vertex (never below its true distance to the
// surface), and the surface's largest distance to the cloud (see surface_side below). Taken once
// over a whole mesh, then, after the mesh has changed, only where it changed: elsewhere every term
// is what it was, so the larger of the new terms and the old estimate is the new estimate. O(n)
// for the whole mesh.
// Choice: for a cloud of more than kPointsPerVertex points per mesh vertex, the cloud's side
// measures every stride-th point only, the stride being the smallest that leaves at most
// kPointsPerVertex per vertex. The estimate guards the repair against moving the surface half an
// edge away from the cloud, which 16 points per vertex (about 8 per triangle) all around a change
// still see; the repair's cost then follows the mesh, not the cloud (36 million points would
// otherwise mean two passes of 36 million nearest-vertex queries). Up to that density every point
// is measured.
class HausdorffEstimate {
public:
    static constexpr std::size_t kPointsPerVertex = 16;
    // The surface's side is sampled finely enough to be within this many mean edge lengths of its
    // true value (see surface_side).
    static constexpr float kSurfaceTolerance = 0.125f;

    // `mean_edge`: the mesh's mean edge length.
    HausdorffEstimate(const Mesh& mesh, const CloudSurface& cloud, float mean_edge)
        : cloud_(cloud), tolerance_(kSurfaceTolerance * mean_edge) {
        const std::vector<Vertex> verts = alive_vertices(mesh);
        const std::unique_ptr<PointGrid> index = position_index(mesh, verts);
        const std::vector<Vec3>& points = cloud.points();
        const std::size_t most = kPointsPerVertex * std::max<std::size_t>(verts.size(), 1);
        stride_ = std::max<std::size_t>(1, (points.size() + most - 1) / most);
        nearest_.reserve(points.size() / stride_ + 1);
        for (std::size_t i = 0; i < points.size(); i += stride_) {
            const Vertex v = verts[index->nearest(points[i])];
            nearest_.push_back(v.idx);
            value_ = std::max(value_, distance_to_ring(mesh, v, points[i]));
        }
        // Each vertex's distance once, rather than once per triangle round it.
        std::vector<float> at_vertex(mesh.vertex_capacity(), 0.0f);
        for (const Vertex v : verts) at_vertex[v.idx] = to_cloud(mesh.position(v));
        value_ = surface_side(mesh, alive_faces(mesh), value_, &at_vertex);
    }

    float value() const { return value_; }

    // The estimate for `mesh`, which differs from the mesh given to the constructor only in the
    // triangles `changed` (and in triangles that no longer exist).
    float after(const Mesh& mesh, const std::vector<Face>& changed) const {
        std::vector<std::uint8_t> affected(mesh.vertex_capacity(), 0);
        for (const Face f : changed)
            if (!mesh.is_removed(f))
                for (const Vertex v : corners(mesh, f)) affected[v.idx] = 1;
        float value = surface_side(mesh, changed, value_);
        const std::vector<Vertex> verts = alive_vertices(mesh);
        const std::unique_ptr<PointGrid> index = position_index(mesh, verts);
        const std::vector<Vec3>& points = cloud_.points();
        for (std::size_t i = 0, k = 0; i < points.size(); i += stride_, ++k) {
            const Vertex v = verts[index->nearest(points[i])];
            // Unchanged: the same nearest vertex, with the same triangles around it.
            if (v.idx == nearest_[k] && !affected[v.idx]) continue;
            value = std::max(value, distance_to_ring(mesh, v, points[i]));
        }
        return value;
    }

private:
    // The largest distance to the cloud of the triangles `faces` (removed ones skipped), or
    // `value` if that is larger, within tolerance_ below the true figure (unless a triangle is
    // more than 2^16 tolerances long). The distance to the cloud changes by at most as much as the
    // point moves, so a triangle comes no farther than a bound from its corners' distances and its
    // longest edge; it is passed over when that does not exceed the largest distance found so far,
    // and cut up (sample_if_farther) otherwise. Most triangles are passed over after their
    // corners; the few that are cut up lie over holes in the scan.
    // Choice: measuring to a tolerance, not at fixed points (corners, edge midpoints, centroids),
    // makes the figure the same for the same surface however it is triangulated. A split of a
    // long edge at its midpoint, which leaves the surface as it was, used to raise the old figure
    // by finding a farther point on a triangle over a hole, and so to undo a repair that had
    // removed every defect (the bunny, 30,000 vertices, seed 9: 210 intersecting pairs kept).
    // `at_vertex`: the vertices' distances to the cloud, by vertex id, when already known.
    float surface_side(const Mesh& mesh, const std::vector<Face>& faces, float value,
                       const std::vector<float>* at_vertex = nullptr) const {
        for (const Face f : faces) {
            if (mesh.is_removed(f)) continue;
            const std::array<Vertex, 3> c = corners(mesh, f);
            float d[3];
            for (int k = 0; k < 3; ++k)
                value = std::max(value, d[k] = at_vertex ? (*at_vertex)[c[k].idx] : to_cloud(mesh.position(c[k])));
            value = sample_if_farther(mesh, c, d, value);
        }
        return value;
    }
    // The triangle with corners c, at distances d from the cloud, for surface_side: the largest
    // distance found on it, or `value` if that is larger. Branch and bound: a triangle whose
    // bound does not exceed `value` is passed over; any other is cut into four at its edges'
    // midpoints (which are measured), down to triangles whose edges are at most tolerance_
    // (every point of those lies within tolerance_ of a measured corner).
    float sample_if_farther(const Mesh& mesh, const std::array<Vertex, 3>& c, const float (&d)[3], float value) const {
        struct Piece {
            Vec3 p[3];
            float d[3];
            int depth;
        };
        constexpr int kMaxDepth = 16;  // also bounds the pieces pending: 3 per level, plus 4
        Piece stack[3 * kMaxDepth + 4];
        int top = 0;
        stack[top++] = {{mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])}, {d[0], d[1], d[2]}, 0};
        while (top > 0) {
            const Piece t = stack[--top];
            const float longest = std::sqrt(
                std::max({squared_distance(t.p[0], t.p[1]), squared_distance(t.p[1], t.p[2]), squared_distance(t.p[2], t.p[0])}));
            // A point of the triangle lies within `longest` of every corner, and within
            // longest / sqrt(3) of the nearest one; the distance to the cloud grows by at most as
            // much as the point moves.
            const float bound = std::min(std::min({t.d[0], t.d[1], t.d[2]}) + longest,
                                         std::max({t.d[0], t.d[1], t.d[2]}) + longest * 0.57736f);
            if (bound <= value || longest <= tolerance_ || t.depth == kMaxDepth) continue;
            Vec3 m[3];
            float dm[3];
            for (int k = 0; k < 3; ++k) {
                m[k] = (t.p[k] + t.p[(k + 1) % 3]) * 0.5f;
                value = std::max(value, dm[k] = to_cloud(m[k]));
            }
            // m[k] is the midpoint of the edge from corner k to corner k + 1.
            stack[top++] = {{t.p[0], m[0], m[2]}, {t.d[0], dm[0], dm[2]}, t.depth + 1};
            stack[top++] = {{m[0], t.p[1], m[1]}, {dm[0], t.d[1], dm[1]}, t.depth + 1};
            stack[top++] = {{m[2], m[1], t.p[2]}, {dm[2], dm[1], t.d[2]}, t.depth + 1};
            stack[top++] = {{m[0], m[1], m[2]}, {dm[0], dm[1], dm[2]}, t.depth + 1};
        }
        return value;
    }
    float to_cloud(const Vec3& p) const { return std::sqrt(cloud_.index().nearest_squared_distance(p)); }

    const CloudSurface& cloud_;
    float tolerance_;
    std::size_t stride_ = 1;
    std::vector<std::uint32_t> nearest_;  // per measured cloud point, its nearest vertex
    float value_ = 0.0f;
};

// ---- a uniform hash grid over triangle bounding boxes ---------------------------------------------

struct Box {
    Vec3 lo, hi;
};

bool overlap(const Box& a, const Box& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

Box face_box(const Mesh& mesh, Face f) {
    const auto c = corners(mesh, f);
    Box b{mesh.position(c[0]), mesh.position(c[0])};
    for (int i = 1; i < 3; ++i) {
        b.lo = min(b.lo, mesh.position(c[i]));
        b.hi = max(b.hi, mesh.position(c[i]));
    }
    return b;
}

// Each face is entered in the bucket of every cell its box overlaps. A pair of faces whose boxes
// overlap is reported from one bucket only, the bucket of the cell holding the minimum corner of
// the boxes' intersection (a hash collision adds candidates, never loses or repeats one).
// Faces whose box covers more than kMaxCells cells are kept apart and compared with every face
// (there are none in a mesh of evenly sized triangles).
class FaceGrid {
public:
    FaceGrid(const Mesh& mesh, const std::vector<Face>& faces, float cell) : inv_cell_(1.0f / cell) {
        std::uint32_t buckets = 16;
        while (buckets < 2 * faces.size()) buckets <<= 1;
        mask_ = buckets - 1;
        start_.assign(buckets + 1, 0);
        items_.reserve(faces.size());
        for (const Face f : faces) {
            const Box b = face_box(mesh, f);
            if (cell_count(b) > kMaxCells) large_.push_back({b, f});
            else items_.push_back({b, f});
        }
        for (const Entry& e : items_) for_each_bucket(e.box, [&](std::uint32_t k) { ++start_[k + 1]; });
        for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
        entries_.resize(start_.back());
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        for (const Entry& e : items_) for_each_bucket(e.box, [&](std::uint32_t k) { entries_[fill[k]++] = e; });
    }

    // Calls visit(f, g) once for every unordered pair of faces of the grid whose boxes overlap.
    template <class Visit>
    void for_each_pair(Visit&& visit) const {
        for (std::uint32_t k = 0; k + 1 < start_.size(); ++k)
            for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i)
                for (std::uint32_t j = i + 1; j < start_[k + 1]; ++j)
                    if (overlap(entries_[i].box, entries_[j].box) && owner(entries_[i].box, entries_[j].box) == k)
                        visit(entries_[i].face, entries_[j].face);
        for (std::size_t i = 0; i < large_.size(); ++i) {
            for (std::size_t j = i + 1; j < large_.size(); ++j)
                if (overlap(large_[i].box, large_[j].box)) visit(large_[i].face, large_[j].face);
            for (const Entry& e : items_)
                if (overlap(large_[i].box, e.box)) visit(large_[i].face, e.face);
        }
    }

    // Calls visit(g) once for every face g of the grid whose box overlaps `box`.
    template <class Visit>
    void for_each_overlapping(const Box& box, Visit&& visit) const {
        if (cell_count(box) > kMaxCells) {
            for (const Entry& e : items_)
                if (overlap(box, e.box)) visit(e.face);
        } else {
            for_each_bucket(box, [&](std::uint32_t k) {
                for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i)
                    if (overlap(box, entries_[i].box) && owner(box, entries_[i].box) == k) visit(entries_[i].face);
            });
        }
        for (const Entry& e : large_)
            if (overlap(box, e.box)) visit(e.face);
    }

private:
    struct Entry {
        Box box;
        Face face;
    };
    struct Cell {
        int x, y, z;
    };
    static constexpr std::uint64_t kMaxCells = 64;

    Cell cell_of(const Vec3& p) const {
        return {int(std::floor(p.x * inv_cell_)), int(std::floor(p.y * inv_cell_)), int(std::floor(p.z * inv_cell_))};
    }
    std::uint32_t bucket(const Cell& c) const {
        return (std::uint32_t(c.x) * 73856093u ^ std::uint32_t(c.y) * 19349663u ^ std::uint32_t(c.z) * 83492791u) & mask_;
    }
    // The bucket a pair of overlapping boxes is reported from.
    std::uint32_t owner(const Box& a, const Box& b) const { return bucket(cell_of(max(a.lo, b.lo))); }
    std::uint64_t cell_count(const Box& b) const {
        const Cell lo = cell_of(b.lo), hi = cell_of(b.hi);
        return std::uint64_t(std::int64_t(hi.x) - lo.x + 1) * std::uint64_t(std::int64_t(hi.y) - lo.y + 1) *
               std::uint64_t(std::int64_t(hi.z) - lo.z + 1);
    }
    // The distinct buckets of the cells a box overlaps (at most kMaxCells cells).
    template <class F>
    void for_each_bucket(const Box& b, F&& f) const {
        const Cell lo = cell_of(b.lo), hi = cell_of(b.hi);
        std::uint32_t seen[kMaxCells];
        int n = 0;
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) {
                    const std::uint32_t k = bucket({x, y, z});
                    if (std::find(seen, seen + n, k) != seen + n) continue;
                    seen[n++] = k;
                    f(k);
                }
    }

    float inv_cell_;
    std::uint32_t mask_ = 0;
    std::vector<std::uint32_t> start_;
    std::vector<Entry> items_;    // the faces of at most kMaxCells cells, once each
    std::vector<Entry> entries_;  // the same, once per bucket of their cells, grouped by bucket
    std::vector<Entry> large_;
};

// Cell size for the face grids: twice the mean largest extent of the triangles' boxes.
float grid_cell(const Mesh& mesh, const std::vector<Face>& faces) {
    double sum = 0.0;
    for (const Face f : faces) {
        const Box b = face_box(mesh, f);
        const Vec3 e = b.hi - b.lo;
        sum += std::max({e.x, e.y, e.z});
    }
    const double mean = faces.empty() ? 0.0 : sum / double(faces.size());
    return mean > 0.0 ? float(2.0 * mean) : 1.0f;
}

// Whether two faces sharing no vertex, both non-degenerate, intersect (the metrics' rule).
bool faces_intersect(const Mesh& mesh, Face f, Face g) {
    const auto s = corners(mesh, f), t = corners(mesh, g);
    for (const Vertex a : s)
        for (const Vertex b : t)
            if (a == b) return false;
    const Vec3 &a = mesh.position(s[0]), &b = mesh.position(s[1]), &c = mesh.position(s[2]);
    const Vec3 &d = mesh.position(t[0]), &e = mesh.position(t[1]), &f3 = mesh.position(t[2]);
    if (squared_norm(cross(b - a, c - a)) == 0.0f || squared_norm(cross(e - d, f3 - d)) == 0.0f) return false;
    return triangles_intersect(a, b, c, d, e, f3);
}

void sort_unique(std::vector<std::pair<Face, Face>>& pairs) {
    for (auto& p : pairs)
        if (p.second < p.first) std::swap(p.first, p.second);
    std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
        return x.first != y.first ? x.first < y.first : x.second < y.second;
    });
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

// ---- the defects of a mesh whose vertices move ----------------------------------------------------

// Folded edges and intersecting pairs, found once over the whole mesh and then kept up to date as
// vertices move and edges collapse or split. A triangle is "changed" once a vertex of it has
// moved (or it was created); a check recomputes the defects of the triangles changed since the
// previous check only: against the never-changed triangles through the grid built at the start
// (their boxes are still right), against the other changed ones through a small grid over the
// changed triangles, rebuilt at each check. Defects between triangles unchanged since the previous
// check are kept as they were.
class DefectTracker {
public:
    DefectTracker(Mesh& mesh, float cos_limit) : mesh_(mesh), cos_limit_(cos_limit) {
        const std::vector<Face> faces = alive_faces(mesh);
        cell_ = grid_cell(mesh, faces);
        grid_ = std::make_unique<FaceGrid>(mesh, faces, cell_);
        grid_->for_each_pair([&](Face f, Face g) {
            if (faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
        });
        sort_unique(pairs_);
        for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
            if (!mesh.is_removed(Edge(e)) && edge_folded(mesh, Mesh::halfedge(Edge(e), 0), cos_limit)) folds_.push_back(Edge(e));
    }

    // The triangles around v changed (v moved, or was created or kept by a split or collapse).
    void changed(Vertex v) {
        mesh_.for_each_face_around(v, [&](Face f) {
            if (f.idx >= state_.size()) state_.resize(mesh_.face_capacity(), 0);
            if (state_[f.idx] != kRecent) {
                if (state_[f.idx] == kUnchanged) changed_.push_back(f);
                state_[f.idx] = kRecent;
                recent_.push_back(f);
            }
        });
    }

    void check() {
        // Collapsed triangles leave the lists, their state cleared, so that a triangle created
        // later in the same slot enters them again.
        auto gone = [&](Face f) {
            if (!mesh_.is_removed(f)) return false;
            state_[f.idx] = kUnchanged;
            return true;
        };
        recent_.erase(std::remove_if(recent_.begin(), recent_.end(), [&](Face f) { return mesh_.is_removed(f); }),
                      recent_.end());
        changed_.erase(std::remove_if(changed_.begin(), changed_.end(), gone), changed_.end());
        std::sort(recent_.begin(), recent_.end());
        std::sort(changed_.begin(), changed_.end());
        // Old defects that involve a recent or collapsed triangle go; the rest stay.
        auto stale = [&](Face f) { return mesh_.is_removed(f) || state(f) == kRecent; };
        pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                                    [&](const auto& p) { return stale(p.first) || stale(p.second); }),
                     pairs_.end());
        folds_.erase(std::remove_if(folds_.begin(), folds_.end(),
                                    [&](Edge e) {
                                        if (mesh_.is_removed(e)) return true;
                                        const Halfedge h = Mesh::halfedge(e, 0);
                                        return stale(mesh_.face(h)) || stale(mesh_.face(Mesh::twin(h)));
                                    }),
                     folds_.end());
        // New defects of the recent triangles.
        const FaceGrid local(mesh_, changed_, cell_);
        for (const Face f : recent_) {
            const Box box = face_box(mesh_, f);
            local.for_each_overlapping(box, [&](Face g) {
                if (g == f || (state(g) == kRecent && g < f)) return;  // a recent pair once
                if (faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
            });
            grid_->for_each_overlapping(box, [&](Face g) {
                if (state(g) != kUnchanged || mesh_.is_removed(g)) return;  // changed: in the small grid
                if (faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
            });
            Halfedge h = mesh_.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh_.next(h)) {
                const Halfedge t = Mesh::twin(h);
                if (state(mesh_.face(t)) == kRecent && t < h) continue;  // an edge between recent ones once
                if (edge_folded(mesh_, h, cos_limit_)) folds_.push_back(Mesh::edge(h));
            }
        }
        sort_unique(pairs_);
        std::sort(folds_.begin(), folds_.end());
        folds_.erase(std::unique(folds_.begin(), folds_.end()), folds_.end());
        for (const Face f : recent_) state_[f.idx] = kChanged;
        recent_.clear();
    }

    bool clean() const { return pairs_.empty() && folds_.empty(); }
    // Every triangle changed so far (some may have been collapsed since), sorted by the last check.
    const std::vector<Face>& changed_faces() const { return changed_; }
    const std::vector<std::pair<Face, Face>>& pairs() const { return pairs_; }
    const std::vector<Edge>& folds() const { return folds_; }
    // The triangles of the defects, sorted, each once.
    std::vector<Face> defective_faces() const {
        std::vector<Face> faces;
        for (const auto& [f, g] : pairs_) faces.insert(faces.end(), {f, g});
        for (const Edge e : folds_) {
            const Halfedge h = Mesh::halfedge(e, 0);
            faces.insert(faces.end(), {mesh_.face(h), mesh_.face(Mesh::twin(h))});
        }
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
        return faces;
    }

private:
    static constexpr std::uint8_t kUnchanged = 0, kChanged = 1, kRecent = 2;
    std::uint8_t state(Face f) const { return f.idx < state_.size() ? state_[f.idx] : kUnchanged; }

    Mesh& mesh_;
    float cos_limit_;
    float cell_ = 1.0f;
    std::unique_ptr<FaceGrid> grid_;
    std::vector<std::uint8_t> state_;  // per face slot
    std::vector<Face> changed_;        // every changed triangle (recent ones included)
    std::vector<Face> recent_;         // changed since the last check
    std::vector<std::pair<Face, Face>> pairs_;
    std::vector<Edge> folds_;
};

// Brings the mesh back to `target` vertices: midpoint splits of its longest edges (which leave the
// surface as it was) when it has fewer, collapses of its shortest edges (the remaining vertex at
// the midpoint) when it has more; changed(v) is told of every vertex whose triangles changed.
// Returns whether the count was reached.
template <class Changed>
bool restore_vertex_count(Mesh& mesh, std::uint32_t target, const std::vector<Face>& near, Changed&& changed) {
    for (int pass = 0; pass < 8 && mesh.n_vertices() != target; ++pass) {
        const std::uint32_t before = mesh.n_vertices();
        const bool grow = before < target;
        // Edges by length, longest first for splits, shortest first for collapses; an edge changed
        // by an earlier operation is recognised by its length and skipped. Only the head of the
        // list that can be needed is sorted. The first pass takes the edges of the triangles
        // `near` (where the caller removed or added vertices), later passes all edges.
        std::vector<std::uint32_t> ids;
        if (pass == 0 && !near.empty()) {
            for (const Face f : near) {
                if (mesh.is_removed(f)) continue;
                Halfedge h = mesh.halfedge(f);
                for (int i = 0; i < 3; ++i, h = mesh.next(h)) ids.push_back(Mesh::edge(h).idx);
            }
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        } else {
            for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
                if (!mesh.is_removed(Edge(e))) ids.push_back(e);
        }
        std::vector<std::pair<float, std::uint32_t>> edges;
        edges.reserve(ids.size());
        for (const std::uint32_t e : ids)
            edges.emplace_back((grow ? -1.0f : 1.0f) * length(mesh, Mesh::halfedge(Edge(e), 0)), e);
        const std::size_t missing = grow ? target - before : before - target;
        const std::size_t head = std::min(edges.size(), 16 * missing + 64);
        std::partial_sort(edges.begin(), edges.begin() + std::ptrdiff_t(head), edges.end());
        edges.resize(head);
        for (const auto& [key, e] : edges) {
            if (mesh.n_vertices() == target) break;
            Halfedge h = Mesh::halfedge(Edge(e), 0);
            if (mesh.is_removed(h) || length(mesh, h) != std::fabs(key)) continue;
            if (grow) {
                changed(split_edge(mesh, h));
                continue;
            }
            if (!mesh.can_collapse(h)) h = Mesh::twin(h);
            if (!mesh.can_collapse(h)) continue;
            const Vertex b = mesh.to(h);
            const Vec3 mid = (mesh.position(mesh.from(h)) + mesh.position(b)) * 0.5f;
            mesh.collapse(h);
            mesh.set_position(b, mid);
            changed(b);
        }
        if (mesh.n_vertices() == before) break;  // no progress
    }
    return mesh.n_vertices() == target;
}

}  // namespace

// ---- pass 1a: flips -------------------------------------------------------------------------------

std::uint64_t flip_to_delaunay(Mesh& mesh, float max_dihedral_deg) {
    const float cos_max = std::cos(max_dihedral_deg * kPiF / 180.0f);
    std::vector<Edge> stack;
    std::vector<std::uint8_t> queued(mesh.edge_capacity(), 0);
    for (std::uint32_t e = mesh.edge_capacity(); e-- > 0;)
        if (!mesh.is_removed(Edge(e))) {
            stack.push_back(Edge(e));
            queued[e] = 1;
        }
    std::uint64_t flips = 0;
    const std::uint64_t limit = 8ull * mesh.n_edges();
    while (!stack.empty() && flips < limit) {
        const Edge e = stack.back();
        stack.pop_back();
        queued[e.idx] = 0;
        const Halfedge h = Mesh::halfedge(e, 0);
        const Vertex a = mesh.from(h), b = mesh.to(h);
        const Vertex c = mesh.to(mesh.next(h)), d = mesh.to(mesh.next(Mesh::twin(h)));
        const Vec3 &pa = mesh.position(a), &pb = mesh.position(b), &pc = mesh.position(c), &pd = mesh.position(d);
        // Not locally Delaunay: the angles opposite the edge sum to more than 180 degrees, that is
        // cot(c) + cot(d) < 0 (with a margin, so that cocircular quads do not flip back and forth).
        if (!(cot_at(pa, pb, pc) + cot_at(pa, pb, pd) < -1e-4f)) continue;
        // Nearly coplanar before and after, the new triangles facing the old ones' side: the flip
        // must not cut across a ridge or fold the surface.
        const Vec3 n0 = normalized(cross(pb - pa, pc - pa)), n1 = normalized(cross(pa - pb, pd - pb));
        if (dot(n0, n1) < cos_max) continue;
        const Vec3 m0 = normalized(cross(pc - pd, pa - pd)), m1 = normalized(cross(pd - pc, pb - pc));
        if (dot(m0, m1) < cos_max) continue;
        const Vec3 side = n0 + n1;
        if (dot(m0, side) <= 0.0f || dot(m1, side) <= 0.0f) continue;
        if (!mesh.can_flip(h)) continue;
        mesh.flip(h);
        ++flips;
        // The four edges of the quad may have stopped being locally Delaunay.
        const Halfedge t = Mesh::twin(h);
        for (const Halfedge g : {mesh.next(h), mesh.next(mesh.next(h)), mesh.next(t), mesh.next(mesh.next(t))}) {
            const Edge ge = Mesh::edge(g);
            if (!queued[ge.idx]) {
                queued[ge.idx] = 1;
                stack.push_back(ge);
            }
        }
    }
    return flips;
}

// ---- pass 1b: tangential relaxation, pulled towards the cloud -------------------------------------

CloudSurface::CloudSurface(const std::vector<Vec3>& points, const Mesh& mesh, const PointGrid* index)
    : points_(points),
      own_index_(index ? nullptr : std::make_unique<PointGrid>(points)),
      index_(index ? index : own_index_.get()) {
    const std::vector<Vertex> verts = alive_vertices(mesh);
    vertex_normals_.resize(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) vertex_normals_[i] = mesh.vertex_normal(verts[i]);
    vertex_index_ = position_index(mesh, verts);
    if (points.size() <= kStoredNormalsPerVertex * verts.size()) {
        point_normals_.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) point_normals_[i] = vertex_normals_[vertex_index_->nearest(points[i])];
    }
}

Vec3 CloudSurface::pull(const Vec3& q, const Vec3& n, float limit, float reach) const {
    return pull(q, n, limit, reach, index_->find_nearest(q));
}

Vec3 CloudSurface::pull(const Vec3& q, const Vec3& n, float limit, float reach, const NearestPoint& near) const {
    if (near.squared_distance > reach * reach || dot(normal(near.index), n) <= 0.0f) return q;
    return q + n * std::clamp(dot(points_[near.index] - q, n), -limit, limit);
}

void relax_tangentially(Mesh& mesh, const CloudSurface* cloud) {
    const std::vector<Vertex> verts = alive_vertices(mesh);
    std::vector<Vec3> next(verts.size());
    const float mean_edge = mean_edge_length(mesh);
    for (std::size_t i = 0; i < verts.size(); ++i) next[i] = relaxed_position(mesh, verts[i], cloud, mean_edge);
    for (std::size_t i = 0; i < verts.size(); ++i) mesh.set_position(verts[i], next[i]);
}

// ---- optional: centroid fit -----------------------------------------------------------------------

void fit_centroids(Mesh& mesh, const std::vector<Vec3>& cloud, float weight) {
    const std::vector<Vertex> verts = alive_vertices(mesh);
    const std::vector<Face> faces = alive_faces(mesh);
    std::vector<Vec3> centroids(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) centroids[i] = mesh.face_centroid(faces[i]);
    const PointGrid index(centroids);
    std::vector<Vec3> pull(mesh.face_capacity());
    std::vector<std::uint32_t> count(mesh.face_capacity(), 0);
    for (const Vec3& x : cloud) {
        const std::uint32_t j = index.nearest(x);
        pull[faces[j].idx] += x - centroids[j];
        ++count[faces[j].idx];
    }
    std::vector<Vec3> next(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) {
        const Vertex v = verts[i];
        const Vec3 p = mesh.position(v);
        Vec3 centroid, normal, sum;
        float area = 0.0f;
        std::uint32_t n_points = 0;
        mesh.for_each_outgoing(v, [&](Halfedge h) {
            const Vec3& q1 = mesh.position(mesh.to(h));
            const Vec3& q2 = mesh.position(mesh.to(mesh.next(h)));
            const Vec3 x = cross(q1 - p, q2 - p);
            const float a = norm(x);
            centroid += (p + q1 + q2) * (a / 3.0f);
            area += a;
            normal += x;
            sum += pull[mesh.face(h).idx];
            n_points += count[mesh.face(h).idx];
        });
        const Vec3 n = normalized(normal);
        Vec3 move;
        if (area > 0.0f) move += (centroid * (1.0f / area) - p) * weight;
        if (n_points > 0) move += sum * (weight / float(n_points));
        next[i] = p + (move - n * dot(move, n));
    }
    for (std::size_t i = 0; i < verts.size(); ++i) mesh.set_position(verts[i], next[i]);
}

// ---- pass 2: folds and self-intersections ---------------------------------------------------------

float estimate_hausdorff(const Mesh& mesh, const CloudSurface& surface) {
    return HausdorffEstimate(mesh, surface, mean_edge_length(mesh)).value();
}

std::vector<std::pair<Face, Face>> find_self_intersections(const Mesh& mesh) {
    const std::vector<Face> faces = alive_faces(mesh);
    const FaceGrid grid(mesh, faces, grid_cell(mesh, faces));
    std::vector<std::pair<Face, Face>> pairs;
    grid.for_each_pair([&](Face f, Face g) {
        if (faces_intersect(mesh, f, g)) pairs.emplace_back(f, g);
    });
    sort_unique(pairs);
    return pairs;
}

std::vector<Edge> find_folded_edges(const Mesh& mesh, float dihedral_deg) {
    const float cos_limit = std::cos(dihedral_deg * kPiF / 180.0f);
    std::vector<Edge> edges;
    for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
        if (!mesh.is_removed(Edge(e)) && edge_folded(mesh, Mesh::halfedge(Edge(e), 0), cos_limit)) edges.push_back(Edge(e));
    return edges;
}

Vertex split_edge(Mesh& mesh, Halfedge h) {
    // Mesh::split of b = from(h) hands the new vertex the half-edges towards x = to(h) and its
    // two ring neighbours c and d; the triangles (a, x, .) replace (b, x, .) and (a, b, c),
    // (b, a, d) fill the rest: with a at the midpoint, the two old triangles, subdivided.
    const Vec3 mid = (mesh.position(mesh.from(h)) + mesh.position(mesh.to(h))) * 0.5f;
    return mesh.split(mesh.cw_rotated(h), mesh.ccw_rotated(h), mid);
}

// Choice: folds and intersections are removed locally, by smoothing and, where smoothing alone
// does not untangle the triangles, by collapsing short edges and splitting long ones. Each round:
//   1. collapses the shortest edge of each defective triangle when it is shorter than a limit
//      (half the mean edge length, growing by a quarter every second round, so that a tangle that
//      smoothing does not undo loses vertices until it does; the remaining vertex at the midpoint);
//   2. splits the longest edge of each defective triangle when it is longer than twice the mean;
//   3. restores the vertex count at once (midpoint splits of the longest edges, or collapses of
//      the shortest, among the triangles changed so far, then anywhere if that is not enough);
//   4. smooths: the corners of the defective triangles move halfway to the mean of their
//      neighbours (twice, Jacobi), the `rings` rings around them the same but only tangentially,
//      so that the surface around a defect does not shrink; the rings grow by one every fourth
//      round;
//   5. tests the changed triangles again (DefectTracker).
// Once no defect is left, the vertices the smoothing moved are pulled back towards the cloud
// (kRefitIterations rounds of relaxed_position), each move kept only where it creates no defect.
// All or nothing: if a defect is left after max_rounds, or the repair raises the Hausdorff
// distance between mesh and cloud (as estimated by HausdorffEstimate) by more
// than half the mean edge length, the mesh is put back as it came. Undoing a tangle may cost some
// fidelity where the tangle was (it followed the data, badly), but only locally.
RepairResult repair_folds_and_intersections(Mesh& mesh, int max_rounds, float fold_dihedral_deg,
                                            const CloudSurface* cloud) {
    RepairResult result;
    DefectTracker tracker(mesh, std::cos(fold_dihedral_deg * kPiF / 180.0f));
    result.intersecting_pairs_before = tracker.pairs().size();
    result.folded_edges_before = tracker.folds().size();
    result.intersecting_pairs = result.intersecting_pairs_before;
    result.folded_edges = result.folded_edges_before;
    if (tracker.clean()) return result;

    const Mesh original = mesh;
    std::unique_ptr<HausdorffEstimate> estimate;
    const float mean_len = mean_edge_length(mesh);
    if (cloud) estimate = std::make_unique<HausdorffEstimate>(mesh, *cloud, mean_len);
    const std::uint32_t target = mesh.n_vertices();
    std::vector<std::uint8_t> level;   // per vertex: 0 outside the region, 1 ring, 2 core
    std::vector<std::uint8_t> smoothed;  // per vertex: moved by a smoothing
    auto grow = [&](std::vector<std::uint8_t>& v) {
        if (v.size() < mesh.vertex_capacity()) v.resize(mesh.vertex_capacity(), 0);
    };
    std::vector<Vertex> region, ring_start, seeds;
    std::vector<Vec3> next;
    for (int round = 0; round < max_rounds && !tracker.clean(); ++round) {
        ++result.rounds;
        const std::vector<Face> defective = tracker.defective_faces();
        seeds.clear();
        // 1. Collapses of short edges.
        const float collapse_below = mean_len * (0.5f + 0.25f * float(round / 2));
        for (const Face f : defective) {
            if (mesh.is_removed(f)) continue;
            Halfedge best;
            float best_len = collapse_below;
            Halfedge h = mesh.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
                const float l = length(mesh, h);
                if (l >= best_len) continue;
                if (mesh.can_collapse(h)) best = h, best_len = l;
                else if (mesh.can_collapse(Mesh::twin(h))) best = Mesh::twin(h), best_len = l;
            }
            if (!best.valid()) continue;
            const Vertex b = mesh.to(best);
            const Vec3 mid = (mesh.position(mesh.from(best)) + mesh.position(b)) * 0.5f;
            mesh.collapse(best);
            mesh.set_position(b, mid);
            tracker.changed(b);
            seeds.push_back(b);
        }
        // 2. Splits of long edges.
        for (const Face f : defective) {
            if (mesh.is_removed(f)) continue;
            Halfedge best;
            float best_len = 2.0f * mean_len;
            Halfedge h = mesh.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
                const float l = length(mesh, h);
                if (l > best_len) best = h, best_len = l;
            }
            if (!best.valid()) continue;
            const Vertex a = split_edge(mesh, best);
            tracker.changed(a);
            seeds.push_back(a);
        }
        // 3. The vertex count, at once (a split can expose two triangles that met at the vertex it
        // moves away from, so its triangles are tested in this round too).
        restore_vertex_count(mesh, target, tracker.changed_faces(), [&](Vertex v) { tracker.changed(v); });
        // 4. The region and the smoothing.
        grow(level);
        grow(smoothed);
        region.clear();
        auto add = [&](Vertex v, std::uint8_t l) {
            if (!level[v.idx]) {
                level[v.idx] = l;
                region.push_back(v);
            }
        };
        for (const Vertex v : seeds)
            if (!mesh.is_removed(v)) add(v, 2);
        for (const Face f : defective)
            if (!mesh.is_removed(f))
                for (const Vertex v : corners(mesh, f)) add(v, 2);
        const int rings = 1 + round / 4;
        for (int r = 0; r < rings; ++r) {
            ring_start = region;
            for (const Vertex v : ring_start) mesh.for_each_neighbor(v, [&](Vertex u) { add(u, 1); });
        }
        std::sort(region.begin(), region.end());
        next.resize(region.size());
        for (int it = 0; it < 2; ++it) {
            for (std::size_t i = 0; i < region.size(); ++i) {
                Vec3 c;
                std::uint32_t k = 0;
                mesh.for_each_neighbor(region[i], [&](Vertex u) {
                    c += mesh.position(u);
                    ++k;
                });
                const Vec3 p = mesh.position(region[i]);
                Vec3 d = (c * (1.0f / float(k)) - p) * 0.5f;
                if (level[region[i].idx] == 1) {
                    const Vec3 n = mesh.vertex_normal(region[i]);
                    d = d - n * dot(d, n);
                }
                next[i] = p + d;
            }
            for (std::size_t i = 0; i < region.size(); ++i) mesh.set_position(region[i], next[i]);
        }
        for (const Vertex v : region) {
            level[v.idx] = 0;
            smoothed[v.idx] = 1;
            tracker.changed(v);
        }
        // 5. Test again.
        tracker.check();
    }
    bool ok = tracker.clean() && mesh.n_vertices() == target;

    // The pull back towards the cloud, guarded.
    if (ok && cloud) {
        std::vector<Vertex> moved;
        for (std::uint32_t v = 0; v < smoothed.size(); ++v)
            if (smoothed[v] && !mesh.is_removed(Vertex(v))) moved.push_back(Vertex(v));
        std::vector<Vec3> before(moved.size());
        for (int it = 0; it < kRefitIterations && !moved.empty(); ++it) {
            for (std::size_t i = 0; i < moved.size(); ++i) before[i] = mesh.position(moved[i]);
            next.resize(moved.size());
            for (std::size_t i = 0; i < moved.size(); ++i) next[i] = relaxed_position(mesh, moved[i], cloud, mean_len);
            for (std::size_t i = 0; i < moved.size(); ++i) {
                mesh.set_position(moved[i], next[i]);
                tracker.changed(moved[i]);
            }
            tracker.check();
            // Undo the moves of the defects' corners until none is left (at worst all of them,
            // which gives back the clean mesh of the previous iteration).
            std::vector<std::uint32_t> slot(mesh.vertex_capacity(), kInvalidIndex);
            for (std::size_t i = 0; i < moved.size(); ++i) slot[moved[i].idx] = std::uint32_t(i);
            for (int undo = 0; undo < 8 && !tracker.clean(); ++undo) {
                for (const Face f : tracker.defective_faces())
                    for (const Vertex v : corners(mesh, f))
                        if (slot[v.idx] != kInvalidIndex) {
                            mesh.set_position(v, before[slot[v.idx]]);
                            tracker.changed(v);
                        }
                tracker.check();
            }
            if (!tracker.clean()) {
                for (std::size_t i = 0; i < moved.size(); ++i) {
                    mesh.set_position(moved[i], before[i]);
                    tracker.changed(moved[i]);
                }
                tracker.check();
                break;
            }
        }
        ok = tracker.clean();
    }
    if (ok && cloud) ok = estimate->after(mesh, tracker.changed_faces()) <= estimate->value() + 0.5f * mean_len;
    if (!ok) {
        mesh = original;
        result.reverted = true;
        return result;
    }
    result.intersecting_pairs = 0;
    result.folded_edges = 0;
    return result;
}

// ---- the stage ------------------------------------------------------------------------------------

bool is_flat(const std::vector<Vec3>& cloud) {
    if (cloud.size() < 4) return true;
    // The plane through three far-apart points, then whether any point lies off it.
    // Choice: the two far points are searched among every stride-th point only (about a million
    // of them at most), so that a large cloud costs a fraction of a pass, plus the test, which
    // stops at the first point off the plane; when those points are all on one line, among all
    // points, as for a cloud of up to 2^21 points.
    const Vec3 a = cloud[0];
    for (std::size_t stride = std::max<std::size_t>(1, cloud.size() >> 20);; stride = 1) {
        Vec3 b = a, c = a;
        float best = -1.0f;
        for (std::size_t i = 0; i < cloud.size(); i += stride)
            if (squared_distance(a, cloud[i]) > best) best = squared_distance(a, cloud[i]), b = cloud[i];
        best = -1.0f;
        for (std::size_t i = 0; i < cloud.size(); i += stride) {
            const float d = squared_norm(cross(cloud[i] - a, b - a));
            if (d > best) best = d, c = cloud[i];
        }
        const Vec3 n = normalized(cross(b - a, c - a));
        if (squared_norm(n) == 0.0f) {
            if (stride == 1) return true;
            continue;
        }
        const float limit = 1e-6f * distance(a, b);
        for (const Vec3& p : cloud)
            if (std::fabs(dot(p - a, n)) > limit) return false;
        return true;
    }
}

FinishReport finish_mesh(Mesh& mesh, const std::vector<Vec3>& cloud, const FinishOptions& options,
                         const PointGrid* cloud_index) {
    const auto start = std::chrono::steady_clock::now();
    FinishReport report;
    mesh.build_faces();  // the learnt mesh comes without its face index (NeuralMesh::mesh)
    if (is_flat(cloud)) {
        report.skipped_flat = true;
        return report;
    }
    const Mesh learnt = options.repair_max_rounds > 0 ? mesh : Mesh();
    // The cloud's point normals come from the learnt mesh, before any pass.
    std::unique_ptr<CloudSurface> surface;
    if (options.project) surface = std::make_unique<CloudSurface>(cloud, mesh, cloud_index);
    const CloudSurface* pull = surface.get();
    for (int r = 0; r < options.rounds; ++r) {
        report.flips += flip_to_delaunay(mesh, options.flip_max_dihedral_deg);
        relax_tangentially(mesh, pull);
        ++report.relax_passes;
    }
    for (int r = 0; r < options.fit_rounds; ++r) {
        fit_centroids(mesh, cloud, options.fit_weight);
        report.flips += flip_to_delaunay(mesh, options.flip_max_dihedral_deg);
    }
    if (options.rounds > 0 || options.fit_rounds > 0) report.flips += flip_to_delaunay(mesh, options.flip_max_dihedral_deg);
    if (options.repair_max_rounds > 0) {
        RepairResult r = repair_folds_and_intersections(mesh, options.repair_max_rounds, options.fold_dihedral_deg, pull);
        report.intersecting_pairs_before = r.intersecting_pairs_before;
        report.folded_edges_before = r.folded_edges_before;
        report.repair_rounds = r.rounds;
        report.repair_reverted = r.reverted;
        // Do no harm: when the repair did not succeed, the regularised mesh is kept only if it
        // has no more intersecting pairs than the learnt one. Otherwise the repair is tried on the
        // learnt mesh itself, and if that fails too the learnt mesh is returned as it was.
        if (r.reverted && (options.rounds > 0 || options.fit_rounds > 0) &&
            r.intersecting_pairs > find_self_intersections(learnt).size()) {
            mesh = learnt;
            r = repair_folds_and_intersections(mesh, options.repair_max_rounds, options.fold_dihedral_deg, pull);
            report.fallback = r.reverted ? FinishReport::Fallback::learnt_mesh : FinishReport::Fallback::repaired_learnt_mesh;
            report.repair_rounds += r.rounds;
        }
        report.intersecting_pairs_after = r.intersecting_pairs;
        report.folded_edges_after = r.folded_edges;
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace nmesh
