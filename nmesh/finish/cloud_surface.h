// nmesh/finish/cloud_surface.h — the cloud as the surface the finishing stage pulls vertices towards.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

// The cloud as the surface the relaxation pulls vertices towards. Each point has a normal, that
// of its nearest vertex in `mesh` (the learnt mesh), which tells the two sides of a part thinner
// than a triangle apart.
// Choice: for a cloud of more than kStoredNormalsPerVertex points per mesh vertex, a point's normal
// is looked up when a pull needs it (its nearest vertex found in an index over the learnt mesh's
// vertices, whose normals are computed once) instead of being stored for every point, so that
// the stage's cost and memory follow the mesh, not the cloud: 36 million points and 30,000
// vertices would otherwise take 36 million nearest-vertex queries and 430 MB of normals, for the
// few hundred thousand pulls of the stage. A smaller cloud keeps them all, computed at once, which
// costs less than a query per pull. Either way a point's normal is the same.
class CloudSurface {
public:
    static constexpr std::size_t kStoredNormalsPerVertex = 8;

    // `points` (and `index`, a nearest-point index over exactly those points, or null to build
    // one) must outlive the object. O(m) for a mesh of m vertices, O(n) more for n points when
    // their normals are stored; plus building `index` when none is given. `sides`, when not null:
    // the points' own normals (one per point, in their order: the side of the surface each was
    // taken from, nmesh/learn/sample_sides.h), used instead of the learnt mesh's, which on a part
    // thinner than a triangle may give a point the other sheet's normal.
    CloudSurface(const std::vector<Vec3>& points, const Mesh& mesh, const PointGrid* index = nullptr,
                 const std::vector<Vec3>* sides = nullptr);
    // q moved along the unit normal n towards the plane through its nearest cloud point (normal
    // n), by at most `limit`; q itself when that point faces the other way (its normal against n)
    // or lies farther than `reach` from q (q is over a hole in the scan).
    Vec3 pull(const Vec3& q, const Vec3& n, float limit, float reach) const;
    // The same with the nearest cloud point to q already known.
    Vec3 pull(const Vec3& q, const Vec3& n, float limit, float reach, const NearestPoint& near) const;
    const std::vector<Vec3>& points() const { return points_; }
    const PointGrid& index() const { return *index_; }
    // The normal of cloud point i: that of its nearest vertex in the learnt mesh.
    const Vec3& normal(std::uint32_t i) const {
        return point_normals_.empty() ? vertex_normals_[vertex_index_->nearest(points_[i])] : point_normals_[i];
    }
    // Whether every point's normal was computed at construction (a cloud of at most
    // kStoredNormalsPerVertex points per mesh vertex).
    bool stores_point_normals() const { return !point_normals_.empty(); }

private:
    const std::vector<Vec3>& points_;
    std::unique_ptr<PointGrid> own_index_;  // when none was given
    const PointGrid* index_;
    std::unique_ptr<PointGrid> vertex_index_;  // over the learnt mesh's vertices
    std::vector<Vec3> vertex_normals_;         // their normals, in the index's order
    std::vector<Vec3> point_normals_;          // per cloud point, or empty (see the choice above)
};

}  // namespace nmesh
