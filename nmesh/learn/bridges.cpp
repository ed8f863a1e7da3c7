#include "nmesh/learn/bridges.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <unordered_map>

#include "nmesh/mesh/face_regions.h"

namespace nmesh {
namespace {

// Edge-connected regions of the faces for which `member` is true: the region of each face slot
// (kInvalidIndex for the others) and the regions' face lists.
struct Regions {
    std::vector<std::uint32_t> of;
    std::vector<std::vector<std::uint32_t>> faces;
};

template <class Member>
Regions regions(const Mesh& mesh, Member&& member) {
    Regions r;
    r.of.assign(mesh.face_capacity(), kInvalidIndex);
    for_each_face_region(mesh, member, [&](const std::vector<std::uint32_t>& faces) {
        for (const std::uint32_t f : faces) r.of[f] = std::uint32_t(r.faces.size());
        r.faces.push_back(faces);
    });
    return r;
}

// 26-connected components of the cells of size `cell` that hold cloud points, for the question
// whether two points are joined through the data.
class CloudCells {
public:
    CloudCells(const PointGrid& cloud, float cell) : inv_(1.0f / cell), points_(cloud.indexed_points()) {
        for (const Vec3& p : points_) cells_.emplace(key(p), 0u);
        std::uint32_t n = 0;
        for (auto& [k, id] : cells_) id = n++;
        parent_.resize(n);
        std::iota(parent_.begin(), parent_.end(), 0u);
        for (const auto& [k, id] : cells_) {
            const std::int64_t x = unpack(k, 0), y = unpack(k, 1), z = unpack(k, 2);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const auto it = cells_.find(pack(x + dx, y + dy, z + dz));
                        if (it != cells_.end()) unite(id, it->second);
                    }
        }
    }
    // Whether the cells of cloud points a and b (indices) are joined.
    bool joined(std::uint32_t a, std::uint32_t b) {
        const auto i = cells_.find(key(points_[a])), j = cells_.find(key(points_[b]));
        return i != cells_.end() && j != cells_.end() && find(i->second) == find(j->second);
    }

private:
    static constexpr std::int64_t kBias = 1 << 20;  // cell coordinates of a normalised cloud are small
    static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
        return (std::uint64_t(x + kBias) << 42) | (std::uint64_t(y + kBias) << 21) | std::uint64_t(z + kBias);
    }
    static std::int64_t unpack(std::uint64_t k, int axis) {
        return std::int64_t((k >> (42 - 21 * axis)) & ((1u << 21) - 1)) - kBias;
    }
    std::uint64_t key(const Vec3& p) const {
        return pack(std::int64_t(std::floor(p.x * inv_)), std::int64_t(std::floor(p.y * inv_)),
                    std::int64_t(std::floor(p.z * inv_)));
    }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) { parent_[find(a)] = find(b); }

    float inv_;
    std::vector<Vec3> points_;
    std::unordered_map<std::uint64_t, std::uint32_t> cells_;
    std::vector<std::uint32_t> parent_;
};

}  // namespace

BridgeSearch find_bridges(const Mesh& mesh, const PointGrid& cloud, const FaceSupport& support) {
    BridgeSearch out;
    out.flagged.assign(mesh.vertex_capacity(), 0);
    if (!mesh.has_faces() || cloud.size() == 0 || support.alive == 0) return out;
    const auto supported = [&](std::uint32_t f) { return !support.unsupported[f]; };
    const Regions parts = regions(mesh, supported);
    if (parts.faces.size() < 2) return out;
    const Regions necks = regions(mesh, [&](std::uint32_t f) { return support.unsupported[f] != 0; });
    std::uint32_t body = 0;
    for (std::uint32_t i = 1; i < parts.faces.size(); ++i)
        if (parts.faces[i].size() > parts.faces[body].size()) body = i;

    std::unique_ptr<CloudCells> cells;  // built for the first candidate
    std::vector<char> in_body(mesh.vertex_capacity(), 0);
    for (const std::uint32_t f : parts.faces[body])
        for (const Vertex v : mesh.face_vertices(Face(f))) in_body[v.idx] = 1;
    for (std::uint32_t i = 0; i < parts.faces.size(); ++i) {
        const std::vector<std::uint32_t>& sac = parts.faces[i];
        if (i == body || sac.size() < kMinSacFaces || double(sac.size()) > kMaxSacShare * support.alive) continue;
        // A disc bounded by a short loop, closed off like a sack.
        std::vector<std::uint32_t> vertices, necks_met;
        std::uint32_t boundary = 0, interior2 = 0;  // boundary edges; interior edges counted twice
        double area = 0.0;
        Vec3 vector_area;
        for (const std::uint32_t f : sac) {
            area += norm(support.data[f].vector_area);
            vector_area += support.data[f].vector_area;
            for (Halfedge h = mesh.halfedge(Face(f)), s = h;;) {
                vertices.push_back(mesh.from(h).idx);
                const Halfedge t = Mesh::twin(h);
                if (!mesh.is_boundary(t) && parts.of[mesh.face(t).idx] == i) {
                    ++interior2;
                } else {
                    ++boundary;
                    if (!mesh.is_boundary(t) && necks.of[mesh.face(t).idx] != kInvalidIndex)
                        necks_met.push_back(necks.of[mesh.face(t).idx]);
                }
                if ((h = mesh.next(h)) == s) break;
            }
        }
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        const std::int64_t euler =
            std::int64_t(vertices.size()) - std::int64_t(boundary + interior2 / 2) + std::int64_t(sac.size());
        if (euler != 1 || boundary > kMaxNeckEdges || norm(vector_area) > kMaxSacFlatness * area) continue;
        // The neck: no more faces than the sac.
        std::sort(necks_met.begin(), necks_met.end());
        necks_met.erase(std::unique(necks_met.begin(), necks_met.end()), necks_met.end());
        std::size_t neck_faces = 0;
        for (const std::uint32_t n : necks_met) neck_faces += necks.faces[n].size();
        if (neck_faces > sac.size() || neck_faces == 0) continue;
        // The neck crosses empty space: the cloud does not wall its middle round (a coarse thin
        // part inside its data, a leg, is walled round, and fills out as the mesh grows).
        Vec3 sac_centre, neck_centre;
        double neck_area = 0.0;
        for (const std::uint32_t f : sac)
            sac_centre += support.data[f].centroid * float(norm(support.data[f].vector_area));
        for (const std::uint32_t n : necks_met)
            for (const std::uint32_t f : necks.faces[n]) {
                const double a = norm(support.data[f].vector_area);
                neck_centre += support.data[f].centroid * float(a);
                neck_area += a;
            }
        if (neck_area <= 0.0 || area <= 0.0) continue;
        sac_centre = sac_centre * float(1.0 / area);
        neck_centre = neck_centre * float(1.0 / neck_area);
        const Vec3 axis = normalized(sac_centre - neck_centre);
        if (squared_norm(axis) == 0.0f ||
            walled_round(cloud, neck_centre, axis, kNeckReach * support.far, 0.5f * support.far))
            continue;
        // Reachable through the data: the nearest cloud points of the sac and of the body.
        if (!cells) cells = std::make_unique<CloudCells>(cloud, support.far);
        if (!cells->joined(cloud.nearest(support.data[sac[0]].centroid),
                           cloud.nearest(support.data[parts.faces[body][0]].centroid)))
            continue;
        ++out.bridges;
        const auto flag = [&](std::uint32_t f) {
            for (const Vertex v : mesh.face_vertices(Face(f)))
                if (!in_body[v.idx] && !out.flagged[v.idx]) out.flagged[v.idx] = 1, ++out.flagged_count;
        };
        for (const std::uint32_t f : sac) flag(f);
        for (const std::uint32_t n : necks_met)
            for (const std::uint32_t f : necks.faces[n]) flag(f);
    }
    return out;
}

std::uint32_t collapse_flagged(Mesh& mesh, const std::vector<char>& flagged,
                               const std::function<void(Vertex gone, Vertex kept)>& collapsed) {
    std::vector<std::uint32_t> left;
    for (std::uint32_t v = 0; v < flagged.size() && v < mesh.vertex_capacity(); ++v)
        if (flagged[v] && !mesh.is_removed(Vertex(v))) left.push_back(v);
    for (bool progress = true; progress && !left.empty();) {
        progress = false;
        std::size_t kept = 0;
        for (const std::uint32_t vi : left) {
            const Vertex v(vi);
            const Vec3 p = mesh.position(v);
            Halfedge best;
            bool best_out = false;  // to an unflagged neighbour
            float best_d2 = 0.0f;
            mesh.for_each_outgoing(v, [&](Halfedge h) {
                const Vertex u = mesh.to(h);
                const bool out = u.idx >= flagged.size() || !flagged[u.idx];
                const float d2 = squared_distance(p, mesh.position(u));
                const bool better = !best.valid() || (out && !best_out) || (out == best_out && d2 < best_d2);
                if (better && mesh.can_collapse(h)) best = h, best_out = out, best_d2 = d2;
            });
            if (!best.valid()) {
                left[kept++] = vi;
                continue;
            }
            const Vertex u = mesh.to(best);
            mesh.collapse(best);
            collapsed(v, u);
            progress = true;
        }
        left.resize(kept);
    }
    return std::uint32_t(left.size());
}

}  // namespace nmesh
