// nmesh/geometry/flatness.h — whether a cloud lies in one plane. A flat cloud's closed mesh must
// fold flat, two coinciding sheets: the learning turns its fold guard off for it and the finishing
// stage leaves it alone, so both ask this.
#pragma once

#include "nmesh/point_span.h"

namespace nmesh {

// Whether all the points lie in one plane (up to 1e-6 of their extent); fewer than 4 points do.
bool is_flat(PointSpan cloud);

}  // namespace nmesh
