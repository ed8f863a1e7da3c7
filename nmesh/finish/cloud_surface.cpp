// nmesh/finish/cloud_surface.cpp — CloudSurface: the cloud's points with normals, and the pull of a vertex towards them.
#include "nmesh/finish/cloud_surface.h"

#include <algorithm>

#include "nmesh/finish/mesh_queries.h"

namespace nmesh {

using namespace finish_detail;

CloudSurface::CloudSurface(const std::vector<Vec3>& points, const Mesh& mesh, const PointGrid* index,
                           const std::vector<Vec3>* sides)
    : points_(points),
      own_index_(index ? nullptr : std::make_unique<PointGrid>(points)),
      index_(index ? index : own_index_.get()) {
    if (sides != nullptr && sides->size() == points.size()) {
        point_normals_ = *sides;
        return;
    }
    const std::vector<Vertex> verts = alive_vertices(mesh);
    vertex_normals_.resize(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) vertex_normals_[i] = mesh.vertex_normal(verts[i]);
    vertex_index_ = position_index(mesh, verts);
    if (points.size() <= kStoredNormalsPerVertex * verts.size()) {
        point_normals_.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            point_normals_[i] = vertex_normals_[vertex_index_->nearest(points[i])];
    }
}

Vec3 CloudSurface::pull(const Vec3& q, const Vec3& n, float limit, float reach) const {
    return pull(q, n, limit, reach, index_->find_nearest(q));
}

Vec3 CloudSurface::pull(const Vec3& q, const Vec3& n, float limit, float reach, const NearestPoint& near) const {
    if (near.squared_distance > reach * reach || dot(normal(near.index), n) <= 0.0f) return q;
    return q + n * std::clamp(dot(points_[near.index] - q, n), -limit, limit);
}

}  // namespace nmesh
