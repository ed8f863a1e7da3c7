// nmesh/finish/face_grid.h — a uniform hash grid over triangle bounding boxes: the broad phase of the
// finishing stage's search for intersecting triangles.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "nmesh/finish/mesh_queries.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/geometry/triangle_intersection.h"

namespace nmesh::finish_detail {

struct Box {
    Vec3 lo, hi;
};

inline bool overlap(const Box& a, const Box& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

inline Box face_box(const Mesh& mesh, Face f) {
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
            if (cell_count(b) > kMaxCells)
                large_.push_back({b, f});
            else
                items_.push_back({b, f});
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
        for_each_pair_in_buckets(0, buckets(), visit);
        for_each_large_pair(visit);
    }
    // The same, in two parts: the pairs reported from buckets [begin, end) (in bucket order: the
    // buckets split into ranges and their pairs joined in the ranges' order give for_each_pair's),
    // then those of the faces kept apart.
    std::uint32_t buckets() const { return std::uint32_t(start_.size() - 1); }
    template <class Visit>
    void for_each_pair_in_buckets(std::uint32_t begin, std::uint32_t end, Visit&& visit) const {
        for (std::uint32_t k = begin; k < end; ++k)
            for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i)
                for (std::uint32_t j = i + 1; j < start_[k + 1]; ++j)
                    if (overlap(entries_[i].box, entries_[j].box) && owner(entries_[i].box, entries_[j].box) == k)
                        visit(entries_[i].face, entries_[j].face);
    }
    template <class Visit>
    void for_each_large_pair(Visit&& visit) const {
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
        return (std::uint32_t(c.x) * 73856093u ^ std::uint32_t(c.y) * 19349663u ^ std::uint32_t(c.z) * 83492791u) &
               mask_;
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
inline float grid_cell(const Mesh& mesh, const std::vector<Face>& faces) {
    double sum = 0.0;
    for (const Face f : faces) {
        const Box b = face_box(mesh, f);
        const Vec3 e = b.hi - b.lo;
        sum += std::max({e.x, e.y, e.z});
    }
    const double mean = faces.empty() ? 0.0 : sum / double(faces.size());
    return mean > 0.0 ? float(2.0 * mean) : 1.0f;
}

// Whether two faces intersect as a defect of the mesh: the exact rule of the metrics
// (nmesh::faces_intersect, which judges faces sharing a vertex or an edge by what they share).
inline bool mesh_faces_intersect(const Mesh& mesh, Face f, Face g) {
    const auto s = corners(mesh, f), t = corners(mesh, g);
    return nmesh::faces_intersect(mesh.positions().data(), {s[0].idx, s[1].idx, s[2].idx},
                                  {t[0].idx, t[1].idx, t[2].idx});
}

inline void sort_unique(std::vector<std::pair<Face, Face>>& pairs) {
    for (auto& p : pairs)
        if (p.second < p.first) std::swap(p.first, p.second);
    std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
        return x.first != y.first ? x.first < y.first : x.second < y.second;
    });
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

}  // namespace nmesh::finish_detail
