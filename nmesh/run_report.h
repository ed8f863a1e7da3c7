// nmesh/run_report.h — the record of one reconstruction as JSON: the input, the parameters, the
// statistics and the quality metrics (what `nmesh reconstruct --stats FILE` writes).
#pragma once

#include <ostream>
#include <string>

#include "nmesh/metrics.h"
#include "nmesh/reconstruct.h"

namespace nmesh {

// `text` as a JSON string literal: quotes, backslashes and control characters escaped; other
// bytes (a path's UTF-8, or whatever its bytes are) copied as they are.
std::string json_string(const std::string& text);

// One JSON object with the keys input, seed, parameters {...}, vertices, faces, the counts and
// timings of Statistics, cancelled and metrics {...} (write_json of the QualityReport), followed
// by a newline. `input` names the cloud (a path, or any label).
void write_run_json(std::ostream& out, const std::string& input, const Parameters& params, const Result& result,
                    const QualityReport& quality);

}  // namespace nmesh
