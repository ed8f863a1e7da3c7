#include "nmesh/learn/handles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nmesh/bounding_box.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/face_regions.h"

namespace nmesh {
namespace {

struct Patch {
    std::vector<std::uint32_t> faces;
    double area = 0.0;
    Vec3 vector_area;  // sum of area-weighted normals
    Vec3 centre;       // area-weighted centroid
    Vec3 normal() const { return normalized(vector_area); }
    float radius() const { return float(std::sqrt(area / 3.14159265358979)); }
};

// Whether the segment pq meets a face outside the two patches (brute force: a few calls per run).
bool segment_blocked(const Mesh& m, const Vec3& p, const Vec3& q, const std::vector<char>& in_pair) {
    for (std::uint32_t f = 0; f < m.face_capacity(); ++f) {
        if (m.is_removed(Face(f)) || in_pair[f]) continue;
        const Halfedge h = m.halfedge(Face(f));
        const Vec3 a = m.position(m.from(h)), b = m.position(m.to(h)), c = m.position(m.to(m.next(h)));
        if (triangle_degenerate(a, b, c)) continue;
        if (segment_intersects_triangle(p, q, a, b, c)) return true;
    }
    return false;
}

// Cuts `patch` out of `m` as one hole: its face nearest the centre first, then, pass after pass,
// every face of the patch beside the hole that can go. Returns a boundary half-edge of the hole,
// or an invalid handle when not even the first face could go.
// Faces with a vertex marked in `avoid` stay.
Halfedge cut_patch(Mesh& m, const Patch& patch, const std::vector<char>& avoid, HandleSearch& out) {
    auto allowed = [&](Face f) {
        for (Halfedge h = m.halfedge(f), s = h;;) {
            if (avoid[m.from(h).idx]) return false;
            if ((h = m.next(h)) == s) break;
        }
        return m.can_remove_face(f);
    };
    std::uint32_t seed = kInvalidIndex;
    float best = std::numeric_limits<float>::max();
    for (std::uint32_t f : patch.faces) {
        const float d = squared_distance(face_data(m, Face(f)).centroid, patch.centre);
        if (d < best && allowed(Face(f))) best = d, seed = f;
    }
    if (seed == kInvalidIndex) return Halfedge();
    const std::size_t own = out.touched_vertices.size();  // this cut's vertices start here
    const Halfedge first = m.halfedge(Face(seed));        // stays alive: a boundary half-edge after the cut
    auto note_vertices = [&](Face f) {
        for (Halfedge h = m.halfedge(f), s = h;;) {
            out.touched_vertices.push_back(m.from(h).idx);
            if ((h = m.next(h)) == s) break;
        }
    };
    note_vertices(Face(seed));
    m.remove_face(Face(seed));
    ++out.faces_removed;
    for (bool progress = true; progress;) {
        progress = false;
        for (std::uint32_t f : patch.faces) {
            const Face face(f);
            if (m.is_removed(face)) continue;
            if (!m.beside_boundary(face) || !allowed(face)) continue;
            note_vertices(face);
            const Vertex gone = m.remove_face(face);
            if (gone.valid()) out.removed_vertices.push_back(gone.idx);
            ++out.faces_removed;
            progress = true;
        }
    }
    // `first` may have gone with an ear or a widening; any boundary half-edge of the hole will do.
    if (!m.is_removed(first) && m.is_boundary(first)) return first;
    for (std::size_t i = own; i < out.touched_vertices.size(); ++i) {
        const Vertex v(out.touched_vertices[i]);
        if (!m.is_removed(v) && m.is_boundary(v)) return m.halfedge(v);
    }
    return Halfedge();
}

// Marks the vertices of `vertices` and their neighbours.
void mark_neighbourhood(const Mesh& m, const std::vector<std::uint32_t>& vertices, std::vector<char>& mark) {
    mark.assign(m.vertex_capacity(), 0);
    for (std::uint32_t v : vertices) {
        if (m.is_removed(Vertex(v))) continue;
        mark[v] = 1;
        m.for_each_outgoing_cw(Vertex(v), [&](Halfedge h) { mark[m.to(h).idx] = 1; });
    }
}

}  // namespace

HandleSearch open_handles(Mesh& mesh, const PointGrid& cloud, const FaceSupport& support) {
    HandleSearch out;
    if (!mesh.has_faces() || mesh.has_boundary() || cloud.size() == 0) return out;
    const std::uint32_t nf = mesh.face_capacity();
    if (support.alive == 0) return out;
    const std::vector<FaceData>& data = support.data;
    const std::vector<char>& unsupported = support.unsupported;
    BoundingBox box;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (!mesh.is_removed(Vertex(v))) box.extend(mesh.position(Vertex(v)));
    const float smallest_hole = kMinHoleRadius * float(box.diagonal());
    const float far = support.far;
    const float far2 = far * far;

    // Patches: edge-connected unsupported faces.
    std::vector<Patch> patches;
    for_each_face_region(mesh, [&](std::uint32_t f) { return unsupported[f] != 0; },
                         [&](const std::vector<std::uint32_t>& faces) {
                             Patch p;
                             p.faces = faces;
                             for (const std::uint32_t g : faces) {
                                 const double a = norm(data[g].vector_area);
                                 p.area += a;
                                 p.vector_area += data[g].vector_area;
                                 p.centre += data[g].centroid * float(a);
                             }
                             if (p.area <= 0.0) return;
                             p.centre = p.centre * float(1.0 / p.area);
                             if (p.faces.size() >= kMinFaces && norm(p.vector_area) >= kMinFlatness * p.area &&
                                 p.radius() >= smallest_hole)
                                 patches.push_back(std::move(p));
                         });
    out.patches = std::uint32_t(patches.size());

    // Pairs, nearest first.
    struct Pair {
        float distance;
        std::uint32_t r, s;
    };
    std::vector<Pair> pairs;
    for (std::uint32_t r = 0; r < patches.size(); ++r)
        for (std::uint32_t s = r + 1; s < patches.size(); ++s) {
            const Patch &pr = patches[r], &ps = patches[s];
            const Vec3 d = ps.centre - pr.centre;
            const float len = norm(d);
            if (len <= 0.0f) continue;
            // Facing away from each other (opposite mean normals), each behind the other: from r
            // to s runs against r's outward normal and back, but for a slack of half the support
            // distance, as two sheets pressed together may lie either way round by that much.
            const float slack = 0.5f * far;
            if (dot(pr.normal(), ps.normal()) > -0.5f) continue;
            if (dot(pr.normal(), d) > slack || dot(ps.normal(), d) < -slack) continue;
            pairs.push_back({len, r, s});
        }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.distance < b.distance; });

    std::vector<char> used(patches.size(), 0), in_pair(nf, 0);
    for (const Pair& pair : pairs) {
        if (used[pair.r] || used[pair.s]) continue;
        const Patch &pr = patches[pair.r], &ps = patches[pair.s];
        // No data along the inner part of the way (the hole is empty), no face across it.
        bool empty = true;
        for (int i = 1; i < 8 && empty; ++i) {
            const float t = float(i) / 8.0f;
            empty = cloud.nearest_squared_distance(pr.centre * (1.0f - t) + ps.centre * t) > far2;
        }
        if (!empty) continue;
        const float reach = 4.0f * std::max(pr.radius(), ps.radius()) + far;
        // The axis from the normals: between two sheets pressed together the centres' offset is
        // mostly sideways.
        const Vec3 axis = normalized(ps.normal() - pr.normal());
        if (!walled_round(cloud, (pr.centre + ps.centre) * 0.5f, axis, reach, 0.5f * far)) continue;
        in_pair.resize(mesh.face_capacity(), 0);  // a join before may have added face slots
        for (std::uint32_t f : pr.faces) in_pair[f] = 1;
        for (std::uint32_t f : ps.faces) in_pair[f] = 1;
        const bool blocked = segment_blocked(mesh, pr.centre, ps.centre, in_pair);
        for (std::uint32_t f : pr.faces) in_pair[f] = 0;
        for (std::uint32_t f : ps.faces) in_pair[f] = 0;
        if (blocked) continue;

        // All or nothing: cut and join on a copy.
        // The two holes keep a ring of faces between them, so that no edge joins their rims
        // already (two sheets pressed together are joined round their fold).
        Mesh trial = mesh;
        HandleSearch step;
        std::vector<std::uint32_t> near;
        for (std::uint32_t f : ps.faces)
            for (Halfedge h = trial.halfedge(Face(f)), s = h;;) {
                near.push_back(trial.from(h).idx);
                if ((h = trial.next(h)) == s) break;
            }
        std::vector<char> avoid;
        mark_neighbourhood(trial, near, avoid);
        const Halfedge a = cut_patch(trial, pr, avoid, step);
        if (!a.valid()) continue;
        mark_neighbourhood(trial, step.touched_vertices, avoid);
        const Halfedge b0 = cut_patch(trial, ps, avoid, step);
        if (!b0.valid()) continue;
        // The join starts at a rim vertex of one hole and the rim vertex of the other nearest to
        // it; when that zip would repeat an edge (rims of two sheets close together can already
        // be joined by one), other starts round the first rim are tried.
        const std::uint32_t m_len = trial.loop_length(a);
        const std::uint32_t tries = std::min<std::uint32_t>(m_len, 8);
        bool joined = false;
        Halfedge start = a;
        for (std::uint32_t t = 0; t < tries && !joined; ++t) {
            for (std::uint32_t i = 0; i < (t == 0 ? 0 : m_len / tries); ++i) start = trial.next(start);
            Halfedge b = b0;
            float best = std::numeric_limits<float>::max();
            for (Halfedge h = b0;;) {
                const float d = squared_distance(trial.position(trial.to(h)), trial.position(trial.from(start)));
                if (d < best) best = d, b = h;
                if ((h = trial.next(h)) == b0) break;
            }
            joined = trial.try_join_loops(start, b);
        }
        if (!joined) continue;
        mesh = std::move(trial);
        used[pair.r] = used[pair.s] = 1;
        ++out.handles;
        out.faces_removed += step.faces_removed;
        out.removed_vertices.insert(out.removed_vertices.end(), step.removed_vertices.begin(),
                                    step.removed_vertices.end());
        out.touched_vertices.insert(out.touched_vertices.end(), step.touched_vertices.begin(),
                                    step.touched_vertices.end());
    }
    // Touched vertices that were deleted later in the same cut are dropped; the rest once each.
    std::sort(out.touched_vertices.begin(), out.touched_vertices.end());
    out.touched_vertices.erase(std::unique(out.touched_vertices.begin(), out.touched_vertices.end()),
                               out.touched_vertices.end());
    out.touched_vertices.erase(std::remove_if(out.touched_vertices.begin(), out.touched_vertices.end(),
                                              [&](std::uint32_t v) { return mesh.is_removed(Vertex(v)); }),
                               out.touched_vertices.end());
    return out;
}

}  // namespace nmesh
