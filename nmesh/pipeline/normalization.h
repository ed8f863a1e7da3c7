// nmesh/pipeline/normalization.h — the pipeline's first stage: the cloud checked and normalised.
#pragma once

#include <cmath>

#include "nmesh/bounding_box.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/point_span.h"
#include "nmesh/spatial/point_transform.h"

namespace nmesh::pipeline {

// The cloud, centred on its bounding box and scaled by a power of two so that its diagonal is
// at most 1. A power-of-two scale is exact in floating point: a cloud and the same cloud scaled
// by 2^k normalise to the same bits, and so give the same mesh up to that scale. The normalised
// points are not stored: the engine applies the transform to each sample as it draws it.
struct Normalization {
    PointTransform transform;  // normalised = (p - center) * scale
    BoundingBox bounds;        // of the normalised points

    // `box`: the bounding box of the cloud.
    explicit Normalization(const BoundingBox& box) {
        transform.center = box.center();
        const double diag = box.diagonal();
        transform.scale = diag > 0.0 ? float(std::ldexp(1.0, -std::ilogb(diag) - 1)) : 1.0f;
        // The box of the normalised points, without another pass over them: each coordinate of
        // transform(p) = (p - center) * scale is a non-decreasing function of the same coordinate
        // of p (float subtraction and multiplication by a positive number round monotonically),
        // so the smallest and largest are the transforms of the input box's corners.
        bounds.extend(transform(box.min));
        bounds.extend(transform(box.max));
    }
    IndexedMesh to_input(IndexedMesh m) const {
        const float inv = 1.0f / transform.scale;
        for (Vec3& p : m.positions) p = p * inv + transform.center;
        return m;
    }
};

// Throws InputError unless the cloud has four affinely independent points (a tetrahedron's
// worth); a flat but not collinear cloud is accepted (the mesh is then a flattened closed
// surface). Returns the cloud's bounding box. Two passes over the cloud (the box; the point
// farthest from the first), then passes that stop at the first point off the line and at the
// fourth distinct point. A non-finite coordinate shows as an infinite box or a NaN distance.
BoundingBox require_reconstructible(PointSpan pts);

}  // namespace nmesh::pipeline
