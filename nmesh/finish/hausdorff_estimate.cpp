// nmesh/finish/hausdorff_estimate.cpp — estimate_hausdorff.
#include "nmesh/finish/hausdorff_estimate.h"

namespace nmesh {

using namespace finish_detail;

float estimate_hausdorff(const Mesh& mesh, const CloudSurface& surface) {
    return HausdorffEstimate(mesh, surface, mean_edge_length(mesh)).value();
}

}  // namespace nmesh
