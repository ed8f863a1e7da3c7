// nmesh/metrics/report_format.cpp — a QualityReport as JSON and as text.
#include <algorithm>
#include <cmath>
#include <locale>
#include <ostream>
#include <sstream>
#include <string>

#include "nmesh/metrics.h"

namespace nmesh {

namespace {

// Calls f(key, text) for every field, in the documented order, values already formatted as JSON.
template <class F>
void for_each_field(const QualityReport& r, F&& f) {
    const auto number = [](double x) {
        if (!std::isfinite(x)) return std::string("null");
        std::ostringstream s;
        s.imbue(std::locale::classic());
        s.precision(10);
        s << x;
        return s.str();
    };
    const auto integer = [](long long x) { return std::to_string(x); };
    const auto boolean = [](bool b) { return std::string(b ? "true" : "false"); };
    f("vertices", integer((long long)r.vertices));
    f("faces", integer((long long)r.faces));
    f("bbox_diagonal", number(r.bbox_diagonal));
    f("dm_x_t", number(r.dm_x_t));
    f("dm_x_t_rel", number(r.dm_x_t_rel));
    f("p2s_mean", number(r.p2s_mean));
    f("p2s_mean_rel", number(r.p2s_mean_rel));
    f("p2s_rms", number(r.p2s_rms));
    f("p2s_rms_rel", number(r.p2s_rms_rel));
    f("p2s_max", number(r.p2s_max));
    f("p2s_max_rel", number(r.p2s_max_rel));
    f("s2p_mean", number(r.s2p_mean));
    f("s2p_mean_rel", number(r.s2p_mean_rel));
    f("s2p_max", number(r.s2p_max));
    f("s2p_max_rel", number(r.s2p_max_rel));
    f("hausdorff", number(r.hausdorff));
    f("hausdorff_rel", number(r.hausdorff_rel));
    f("closed", boolean(r.closed));
    f("manifold", boolean(r.manifold));
    f("euler", integer(r.euler));
    f("genus", r.genus < 0 ? std::string("null") : integer(r.genus));
    f("components", integer((long long)r.components));
    f("isolated_vertices", integer((long long)r.isolated_vertices));
    f("boundary_loops", integer((long long)r.boundary_loops));
    f("boundary_edges", integer((long long)r.boundary_edges));
    f("boundary_length", number(r.boundary_length));
    f("boundary_length_rel", number(r.boundary_length_rel));
    f("degenerate_triangles", integer((long long)r.degenerate_triangles));
    f("self_intersections", integer((long long)r.self_intersections));
    f("signed_volume", number(r.signed_volume));
    f("inward_faces", integer((long long)r.inward_faces));
    f("min_angle_min_deg", number(r.min_angle_min_deg));
    f("min_angle_mean_deg", number(r.min_angle_mean_deg));
    f("share_under_10deg", number(r.share_under_10deg));
}

}  // namespace

void write_json(std::ostream& out, const QualityReport& report) {
    std::string text = "{";
    bool first = true;
    for_each_field(report, [&](const char* key, const std::string& value) {
        text += first ? "\n  \"" : ",\n  \"";
        text += key;
        text += "\": ";
        text += value;
        first = false;
    });
    text += "\n}";
    out << text;
}

void write_text(std::ostream& out, const QualityReport& report) {
    std::string text;
    for_each_field(report, [&](const char* key, const std::string& value) {
        std::string line = key;
        line += ':';
        line.resize(std::max<std::size_t>(line.size() + 1, 22), ' ');
        text += line + (value == "null" ? "-" : value) + "\n";
    });
    out << text;
}

}  // namespace nmesh
