// nmesh/pipeline/opening.h — the pipeline's opening stage (topology open): the learnt mesh
// finished and cut open where the cloud has no data (nmesh/finish/open_surface.h).
#pragma once

#include <memory>

#include "nmesh/mesh/mesh.h"
#include "nmesh/parameters.h"
#include "nmesh/pipeline/normalization.h"
#include "nmesh/pipeline/reporter.h"
#include "nmesh/point_span.h"
#include "nmesh/reconstruct.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh::pipeline {

// Topology open (nmesh/finish/open_surface.h): on a partial view, the view's sheet made again
// from the learnt vertices (nmesh/finish/view_sheet.h); then each piece finished (when
// `finish`), cut where the cloud has no data, and the pieces joined without the faces of
// crossing pairs. Sets result.mesh and the open counts, and
// stats.finished when every piece was finished. Unless `last` (no output retry left), crossings
// on a closed object's mesh are left for the output check, so that the learning tries another
// path from its checkpoint before any face is cut; a view's sheet is cut at once (its crossings
// come from the finishing stage's relaxation, not from the path the learning took).
void open_output(Mesh& learnt, bool finish, bool last, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                 const Normalization& norm, const Parameters& params, Reporter& reporter, Result& result);

}  // namespace nmesh::pipeline
