// nmesh/finish/defect_tracker.h — the folded edges and intersecting triangle pairs of a mesh whose vertices
// move, kept up to date by the repair.
#pragma once

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/finish/face_grid.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/finish/repair.h"  // split_edge, for restore_vertex_count
#include "nmesh/mesh/mesh.h"
#include "nmesh/util/parallel.h"

namespace nmesh::finish_detail {

// Folded edges and intersecting pairs, found once over the whole mesh and then kept up to date as
// vertices move and edges collapse or split. A triangle is "changed" once a vertex of it has
// moved (or it was created); a check recomputes the defects of the triangles changed since the
// previous check only: against the never-changed triangles through the grid built at the start
// (their boxes are still right), against the other changed ones through a small grid over the
// changed triangles, rebuilt at each check. Defects between triangles unchanged since the previous
// check are kept as they were.
class DefectTracker {
public:
    // `known_clean`: the caller knows the mesh has no defect (the repair's result), and the
    // search over the whole mesh, most of the construction's cost, is skipped. That search runs
    // on `threads` (0: the machine's cores), the grid's buckets in fixed ranges, each range's pairs
    // kept apart and joined in the ranges' order: the same pairs for any count.
    DefectTracker(Mesh& mesh, float cos_limit, bool known_clean = false, std::uint32_t threads = 1)
        : mesh_(mesh), cos_limit_(cos_limit) {
        const std::vector<Face> faces = alive_faces(mesh);
        cell_ = grid_cell(mesh, faces);
        grid_ = std::make_unique<FaceGrid>(mesh, faces, cell_);
        if (known_clean) return;
        constexpr std::uint32_t kBucketsPerChunk = 1024;
        const std::uint32_t buckets = grid_->buckets();
        std::vector<std::vector<std::pair<Face, Face>>> found((buckets + kBucketsPerChunk - 1) / kBucketsPerChunk);
        const Mesh& shape = mesh;
        for_chunks(buckets, kBucketsPerChunk, threads, [&](std::size_t begin, std::size_t end) {
            auto& mine = found[begin / kBucketsPerChunk];
            grid_->for_each_pair_in_buckets(std::uint32_t(begin), std::uint32_t(end), [&](Face f, Face g) {
                if (mesh_faces_intersect(shape, f, g)) mine.emplace_back(f, g);
            });
        });
        for (const auto& part : found) pairs_.insert(pairs_.end(), part.begin(), part.end());
        grid_->for_each_large_pair([&](Face f, Face g) {
            if (mesh_faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
        });
        sort_unique(pairs_);
        for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
            if (!mesh.is_removed(Edge(e)) && edge_folded(mesh, Mesh::halfedge(Edge(e), 0), cos_limit))
                folds_.push_back(Edge(e));
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
                if (mesh_faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
            });
            grid_->for_each_overlapping(box, [&](Face g) {
                if (state(g) != kUnchanged || mesh_.is_removed(g)) return;  // changed: in the small grid
                if (mesh_faces_intersect(mesh_, f, g)) pairs_.emplace_back(f, g);
            });
            Halfedge h = mesh_.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh_.next(h)) {
                const Halfedge t = Mesh::twin(h);
                if (mesh_.is_boundary(t)) continue;                      // one triangle: no fold
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
                const Vertex a = split_edge(mesh, h);
                if (a.valid()) changed(a);
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

}  // namespace nmesh::finish_detail
