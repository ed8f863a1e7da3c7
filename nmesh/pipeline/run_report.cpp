#include "nmesh/run_report.h"

#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>

#include "nmesh/util/parallel.h"

namespace nmesh {

// `text` as a JSON string literal: quotes, backslashes and control characters escaped; other
// bytes (a path's UTF-8, or whatever its bytes are) copied as they are.
std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
                    out += buf;
                } else {
                    out += ch;
                }
        }
    }
    return out + "\"";
}

void write_run_json(std::ostream& o, const std::string& input, const Parameters& p, const Result& r,
                    const QualityReport& q) {
    const Statistics& s = r.stats;
    std::ostringstream metrics;
    write_json(metrics, q);
    const auto old_precision = o.precision();
    o.precision(10);
    o << "{\n"
      << "  \"input\": " << json_string(input) << ",\n"
      << "  \"seed\": " << p.seed << ",\n"
      << "  \"parameters\": {\"target_vertices\": " << p.target_vertices << ", \"alpha_w\": " << p.alpha_w
      << ", \"alpha_n\": " << p.alpha_n << ", \"alpha\": " << p.alpha << ", \"cvs\": " << p.cvs
      << ", \"cec\": " << p.cec << ", \"edge_swap\": " << (p.edge_swap ? "true" : "false")
      << ", \"fold_guard\": " << (p.fold_guard ? "true" : "false")
      << ", \"solid_start\": " << (p.solid_start ? "true" : "false") << ", \"topology\": \"" << topology_name(p.topology)
      << "\", \"settle\": " << p.settle << ", \"finish\": " << (p.finish ? "true" : "false")
      << ", \"finish_rounds\": " << p.finish_rounds << ", \"fit_rounds\": " << p.fit_rounds
      << ", \"surface_fit_rounds\": " << p.surface_fit_rounds << ", \"exchange_passes\": " << p.exchange_passes
      << ", \"min_hole\": " << p.min_hole
      << ", \"stray_ratio\": " << p.stray_ratio
      << ", \"adaptivity\": " << p.adaptivity
      << ", \"index_points_per_vertex\": " << p.index_points_per_vertex
      << ", \"threads\": " << resolve_threads(p.threads) << "},\n"
      << "  \"vertices\": " << r.mesh.positions.size() << ",\n"
      << "  \"faces\": " << r.mesh.triangles.size() << ",\n"
      << "  \"iterations\": " << s.iterations << ",\n"
      << "  \"settle_iterations\": " << s.settle_iterations << ",\n"
      << "  \"splits\": " << s.splits << ",\n"
      << "  \"collapses\": " << s.collapses << ",\n"
      << "  \"collapses_refused\": " << s.collapses_refused << ",\n"
      << "  \"swaps_tried\": " << s.swaps_tried << ",\n"
      << "  \"swaps_kept\": " << s.swaps_kept << ",\n"
      << "  \"swaps_undone\": " << s.swaps_undone << ",\n"
      << "  \"swaps_illegal\": " << s.swaps_illegal << ",\n"
      << "  \"moves_shortened\": " << s.moves_shortened << ",\n"
      << "  \"folds_undone\": " << s.folds_undone << ",\n"
      << "  \"side_skips\": " << s.side_skips << ",\n"
      << "  \"twist_checks\": " << s.twist_checks << ",\n"
      << "  \"twist_retries\": " << s.twist_retries << ",\n"
      << "  \"twists_kept\": " << s.twists_kept << ",\n"
      << "  \"output_retries\": " << s.output_retries << ",\n"
      << "  \"solid_genus\": " << s.solid_genus << ",\n"
      << "  \"start_retries\": " << s.start_retries << ",\n"
      << "  \"stray_points\": " << s.stray_points << ",\n"
      << "  \"cloud_parts\": " << s.cloud_parts << ",\n"
      << "  \"parts_apart\": " << (s.parts_apart ? "true" : "false") << ",\n"
      << "  \"start_vertices\": " << s.start_vertices << ",\n"
      << "  \"start_core\": " << (s.start_core ? "true" : "false") << ",\n"
      << "  \"topology_checks\": " << s.topology_checks << ",\n"
      << "  \"membrane_patches\": " << s.membrane_patches << ",\n"
      << "  \"handles\": " << s.handles << ",\n"
      << "  \"membrane_faces_removed\": " << s.membrane_faces_removed << ",\n"
      << "  \"bridges\": " << s.bridges << ",\n"
      << "  \"bridge_vertices_removed\": " << s.bridge_vertices_removed << ",\n"
      << "  \"layer_faces_removed\": " << s.layer_faces_removed << ",\n"
      << "  \"open_faces_removed\": " << s.open_faces_removed << ",\n"
      << "  \"crossing_faces_removed\": " << s.crossing_faces_removed << ",\n"
      << "  \"open_vertices_added\": " << s.open_vertices_added << ",\n"
      << "  \"indexed_points\": " << s.indexed_points << ",\n"
      << "  \"seconds\": " << s.seconds << ",\n"
      << "  \"seconds_finish\": " << s.seconds_finish << ",\n"
      << "  \"repair_declined\": " << (s.repair_declined ? "true" : "false") << ",\n"
      << "  \"reoriented\": " << (s.reoriented ? "true" : "false") << ",\n"
      << "  \"genus\": " << s.genus << ",\n"
      << "  \"boundary_loops\": " << s.boundary_loops << ",\n"
      << "  \"crossing_pairs\": " << s.crossing_pairs << ",\n"
      << "  \"inward_faces\": " << s.inward_faces << ",\n"
      << "  \"cancelled\": " << (r.cancelled ? "true" : "false") << ",\n"
      << "  \"metrics\": " << metrics.str() << "\n"
      << "}\n";
    o.precision(old_precision);
}

}  // namespace nmesh
