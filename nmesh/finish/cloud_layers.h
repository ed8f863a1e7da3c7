// nmesh/finish/cloud_layers.h — whether a cloud is one layer seen from some direction: a single
// range image, not a closed object.
//
// A scanner sees a surface from one side: looked at along its direction, the points of a range
// image lie in one layer over their outline (two only where one part hides another, at an ear's
// tip). A closed object, or an open one wrapped round a volume (a scan with holes), has two layers
// or more over nearly all of its outline, seen from any direction: its near and far sides. The
// test projects the points along each of the 13 directions of a cube's faces, edges and corners,
// onto cells one spacing across, and counts the occupied cells whose points' depths leave a gap
// wider than two spacings; the share of such cells along the best direction is the cloud's
// multi-layer share. Measured (docs/algorithm.md, "Open surfaces"): the four single range images
// 0.013-0.038, every closed cloud of the shared data and the corpus 0.43 (the rocker arm) to 0.76,
// the bull with its 90 holes 0.44 (the cells at the outline, seen edge-on, and those with one
// point, are one layer on any cloud). A share, not a length: the same at any density and scale.
#pragma once

#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

// A partial view: a multi-layer share under this, about half of the lowest share of a closed
// cloud and six times the highest of a range image.
inline constexpr float kViewLayerShare = 0.25f;

// The multi-layer share of `points` (see above); `spacing`: their typical local spacing (the cells'
// size, and half the gap between layers). 1 for fewer than two points. O(13 n log n).
float multi_layer_share(const std::vector<Vec3>& points, float spacing);

}  // namespace nmesh
