// nmesh/pipeline/output_check.h — the pipeline's last stage: the output turned to face outward
// and checked exactly for crossing triangles and inward faces.
#pragma once

#include "nmesh/reconstruct.h"

namespace nmesh::pipeline {

// Every closed output faces outward (its triangles reversed when the learning turned the whole
// surface inside out), and its validity is measured: crossing pairs and, for a closed one, inward
// faces; its genus and boundary loops are counted. The faces' tests run on `threads` threads
// (Parameters::threads), with the same counts for any number.
void check_output(Result& result, std::uint32_t threads = 1);

}  // namespace nmesh::pipeline
