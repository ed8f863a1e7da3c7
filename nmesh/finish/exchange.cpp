// The vertex exchange of the finishing stage (nmesh/finish/exchange.h).
#include "nmesh/finish/exchange.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "nmesh/finish/mesh_queries.h"
#include "nmesh/finish/regularise.h"
#include "nmesh/finish/repair.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/util/math_constants.h"

namespace nmesh {

using namespace finish_detail;

namespace {

// A collapse looks this far down the list of splits for one clear of its reach.
constexpr std::size_t kSplitsLooked = 64;

struct Candidate {
    float value = 0.0f;
    Halfedge h;
};

bool touches_boundary(const Mesh& mesh, Halfedge h) {
    return mesh.is_boundary(mesh.from(h)) || mesh.is_boundary(mesh.to(h));
}

// A vertex's quadric about itself, sum over its triangles of area x n n^T (n the unit normal): the
// cost of moving it by d onto a neighbour is d^T Q d, the area times the squared distance of the
// neighbour to each of its triangles' planes (zero for the triangles the neighbour is in).
struct Quadric {
    float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    float of(const Vec3& d) const {
        return xx * d.x * d.x + yy * d.y * d.y + zz * d.z * d.z + 2.0f * (xy * d.x * d.y + xz * d.x * d.z + yz * d.y * d.z);
    }
};

Quadric vertex_quadric(const Mesh& mesh, Vertex a) {
    Quadric q;
    const Vec3 pa = mesh.position(a);
    mesh.for_each_corner(a, [&](Halfedge c) {
        const Vec3 x = cross(mesh.position(mesh.to(c)) - pa, mesh.position(mesh.to(mesh.next(c))) - pa);
        const float twice_area = norm(x);
        if (!(twice_area > 0.0f)) return;
        const Vec3 n = x * (1.0f / twice_area);
        const float w = 0.5f * twice_area;
        q.xx += w * n.x * n.x;
        q.xy += w * n.x * n.y;
        q.xz += w * n.x * n.z;
        q.yy += w * n.y * n.y;
        q.yz += w * n.y * n.z;
        q.zz += w * n.z * n.z;
    });
    return q;
}

// Whether collapsing h = (a -> b), b staying, turns none of a's triangles by more than the limit
// (nor flattens one).
bool collapse_keeps_turns(const Mesh& mesh, Halfedge h, float cos_turn) {
    const Vertex a = mesh.from(h), b = mesh.to(h);
    const Vec3 pa = mesh.position(a), pb = mesh.position(b);
    bool ok = true;
    mesh.for_each_corner(a, [&](Halfedge c) {
        const Vertex q1 = mesh.to(c), q2 = mesh.to(mesh.next(c));
        if (!ok || q1 == b || q2 == b) return;  // goes with the edge
        const Vec3 x1 = mesh.position(q1), x2 = mesh.position(q2);
        const Vec3 before = cross(x1 - pa, x2 - pa), after = cross(x1 - pb, x2 - pb);
        const float lb = norm(before), la = norm(after);
        ok = lb > 0.0f && la > 0.0f && dot(before, after) >= cos_turn * lb * la;
    });
    return ok;
}

}  // namespace

ExchangeResult exchange_vertices(Mesh& mesh, const CloudSurface& cloud, int passes, float flip_max_dihedral_deg) {
    ExchangeResult result;
    const float cos_turn = std::cos(kExchangeTurnDeg * kPi / 180.0f);
    std::vector<Candidate> collapses, splits;
    std::vector<Vec3> split_at(mesh.edge_capacity());
    std::vector<std::uint8_t> locked;
    std::vector<Vertex> set;
    std::vector<Quadric> quadrics;
    for (int pass = 0; pass < passes; ++pass) {
        collapses.clear();
        splits.clear();
        split_at.resize(mesh.edge_capacity());
        quadrics.assign(mesh.vertex_capacity(), Quadric());
        for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
            if (!mesh.is_removed(Vertex(v))) quadrics[v] = vertex_quadric(mesh, Vertex(v));
        for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e) {
            if (mesh.is_removed(Edge(e))) continue;
            const Halfedge h = Mesh::halfedge(Edge(e), 0);
            if (mesh.is_boundary(Edge(e)) || touches_boundary(mesh, h)) continue;
            // The collapse, the cheaper direction (h takes from(h) onto to(h)).
            const Vec3 d = mesh.position(mesh.to(h)) - mesh.position(mesh.from(h));
            const float c0 = quadrics[mesh.from(h).idx].of(d), c1 = quadrics[mesh.to(h).idx].of(d);
            collapses.push_back({std::min(c0, c1), c0 <= c1 ? h : Mesh::twin(h)});
        }
        // The splits: each face's bias, the mean signed distance of the points nearest its centroid
        // from its plane (noise averages out; a chord under a bend does not).
        const std::vector<Face> faces = alive_faces(mesh);
        std::vector<Vec3> centroids(faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i) centroids[i] = mesh.face_centroid(faces[i]);
        const PointGrid face_index(centroids);
        std::vector<double> bias_sum(mesh.face_capacity(), 0.0);
        std::vector<double> square_sum(mesh.face_capacity(), 0.0);
        std::vector<std::uint32_t> bias_count(mesh.face_capacity(), 0);
        const float mean_edge = mean_edge_length(mesh);
        const auto& points = cloud.points();
        const std::size_t stride = std::max<std::size_t>(1, points.size() / (16 * std::size_t(mesh.n_vertices()) + 1));
        // Only the points near the mesh's box are looked up (the mesh may be one piece of a cloud
        // in several: a query far from the centroids costs a search through empty cells).
        Vec3 low = centroids.empty() ? Vec3() : centroids[0], high = low;
        for (const Vec3& c : centroids) {
            low = Vec3(std::min(low.x, c.x), std::min(low.y, c.y), std::min(low.z, c.z));
            high = Vec3(std::max(high.x, c.x), std::max(high.y, c.y), std::max(high.z, c.z));
        }
        for (std::size_t i = 0; i < points.size(); i += stride) {
            const Vec3& x = points[i];
            if (x.x < low.x - mean_edge || x.y < low.y - mean_edge || x.z < low.z - mean_edge ||
                x.x > high.x + mean_edge || x.y > high.y + mean_edge || x.z > high.z + mean_edge)
                continue;
            const NearestPoint near = face_index.find_nearest(points[i]);
            if (near.squared_distance > mean_edge * mean_edge) continue;
            const Face f = faces[near.index];
            const Vec3 n = normalized(area_vector(mesh, f));
            if (dot(cloud.normal(std::uint32_t(i)), n) <= 0.0f) continue;  // the other side of a thin part
            const double d = dot(points[i] - centroids[near.index], n);
            bias_sum[f.idx] += d;
            square_sum[f.idx] += d * d;
            ++bias_count[f.idx];
        }
        // The scan's noise across a face, pooled over the faces with two points or more: the part
        // of a face's squared bias that a mean over its few points has from the noise alone.
        double scatter = 0.0, dof = 0.0;
        for (const Face f : faces) {
            const std::uint32_t c = bias_count[f.idx];
            if (c < 2) continue;
            scatter += square_sum[f.idx] - bias_sum[f.idx] * bias_sum[f.idx] / c;
            dof += c - 1;
        }
        const double noise = dof > 0.0 ? scatter / dof : 0.0;
        for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e) {
            if (mesh.is_removed(Edge(e))) continue;
            const Halfedge h = Mesh::halfedge(Edge(e), 0);
            if (mesh.is_boundary(Edge(e)) || touches_boundary(mesh, h)) continue;
            const float len = length(mesh, h);
            float gain = 0.0f, sag = 0.0f, wsum = 0.0f;
            Vec3 n;
            for (const Halfedge k : {h, Mesh::twin(h)}) {
                const Face f = mesh.face(k);
                const Vec3 av = area_vector(mesh, f);
                n += av;
                if (bias_count[f.idx] == 0) continue;
                const float longest = std::max({len, length(mesh, mesh.next(k)), length(mesh, mesh.next(mesh.next(k)))});
                const float b = float(bias_sum[f.idx] / bias_count[f.idx]);
                const float share = (len / longest) * (len / longest);
                const float excess = float(std::max(0.0, double(b) * b - noise / bias_count[f.idx]));
                gain += 0.5f * norm(av) * excess * share;
                sag += b * share;
                wsum += share;
            }
            if (!(gain > 0.0f)) continue;
            const Vec3 mid = (mesh.position(mesh.from(h)) + mesh.position(mesh.to(h))) * 0.5f;
            // The new vertex goes as far as the faces' bias, within a quarter of the edge.
            split_at[e] = mid + normalized(n) * std::clamp(sag / wsum, -0.25f * len, 0.25f * len);
            splits.push_back({gain, h});
        }
        std::sort(collapses.begin(), collapses.end(), [](const Candidate& x, const Candidate& y) {
            return x.value < y.value || (x.value == y.value && x.h < y.h);
        });
        std::sort(splits.begin(), splits.end(), [](const Candidate& x, const Candidate& y) {
            return x.value > y.value || (x.value == y.value && x.h < y.h);
        });
        locked.assign(mesh.vertex_capacity() + 2 * std::size_t(kExchangeShare * float(mesh.n_vertices()) + 2), 0);
        const std::uint64_t max_pairs = std::uint64_t(kExchangeShare * float(mesh.n_vertices())) + 1;
        std::uint64_t pairs = 0;
        std::size_t si = 0;
        const auto is_locked = [&](Vertex v) { return v.idx < locked.size() && locked[v.idx]; };
        // A candidate's edge is gone when an operation of the pass took it (its slot free, or
        // reused by a new edge at a locked vertex): it is read only when it is live.
        const auto split_vertices = [&](Halfedge h) {
            return std::array<Vertex, 4>{mesh.from(h), mesh.to(h), mesh.to(mesh.next(h)),
                                         mesh.to(mesh.next(Mesh::twin(h)))};
        };
        const auto split_blocked = [&](Halfedge h) {
            if (mesh.is_removed(Mesh::edge(h))) return true;
            const auto q = split_vertices(h);
            return std::any_of(q.begin(), q.end(), is_locked);
        };
        for (std::size_t ci = 0; ci < collapses.size() && pairs < max_pairs; ++ci) {
            const Candidate& c = collapses[ci];
            while (si < splits.size() && split_blocked(splits[si].h)) ++si;
            if (si == splits.size() || splits[si].value <= kExchangeMargin * c.value) break;
            if (mesh.is_removed(Mesh::edge(c.h))) continue;
            // The collapse's reach: both rings.
            const Vertex a = mesh.from(c.h), b = mesh.to(c.h);
            set.clear();
            set.push_back(a);
            set.push_back(b);
            mesh.for_each_neighbor(a, [&](Vertex v) { set.push_back(v); });
            mesh.for_each_neighbor(b, [&](Vertex v) { set.push_back(v); });
            if (std::any_of(set.begin(), set.end(), is_locked)) continue;
            if (mesh.valence(a) + mesh.valence(b) - 4 > kExchangeMaxValence || !mesh.can_collapse(c.h) ||
                !collapse_keeps_turns(mesh, c.h, cos_turn))
                continue;
            // The first split clear of the collapse's reach and worth it, among the next
            // kSplitsLooked: the splits taken by the pass leave locked ones in the list, and a
            // search through all of them for every collapse would cost collapses x splits.
            std::size_t sj = si;
            bool found = false;
            for (std::size_t looked = 0; sj < splits.size() && looked < kSplitsLooked &&
                                         splits[sj].value > kExchangeMargin * c.value;
                 ++sj, ++looked) {
                if (split_blocked(splits[sj].h)) continue;
                const auto q = split_vertices(splits[sj].h);
                found = std::none_of(q.begin(), q.end(),
                                     [&](Vertex v) { return std::find(set.begin(), set.end(), v) != set.end(); });
                if (found) break;
            }
            if (!found) continue;
            const Halfedge sh = splits[sj].h;
            const auto q = split_vertices(sh);
            const Vec3 to = split_at[Mesh::edge(sh).idx];
            mesh.collapse(c.h);
            const Vertex added = split_edge(mesh, sh);  // valid: no end of sh is on a boundary
            mesh.set_position(added, to);
            for (const Vertex v : set) locked[v.idx] = 1;
            for (const Vertex v : q) locked[v.idx] = 1;
            if (added.idx >= locked.size()) locked.resize(added.idx + 1, 0);
            locked[added.idx] = 1;
            ++pairs;
        }
        ++result.passes;
        result.exchanged += pairs;
        flip_to_delaunay(mesh, flip_max_dihedral_deg);
        if (pairs == 0) break;
    }
    return result;
}

}  // namespace nmesh
