#include "nmesh/parameters.h"

#include <string>

#include "nmesh/error.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

const char* topology_name(Topology t) {
    return t == Topology::open ? "open" : t == Topology::closed ? "closed" : "sphere";
}

Topology parse_topology(const char* name) {
    const std::string s = name ? name : "";
    if (s == "sphere") return Topology::sphere;
    if (s == "closed") return Topology::closed;
    if (s == "open") return Topology::open;
    throw ParameterError("topology", "invalid parameter topology: must be sphere, closed or open, got '" + s + "'");
}

void Parameters::validate() const {
    auto bad = [](const std::string& name, const std::string& why) {
        throw ParameterError(name, "invalid parameter " + name + ": " + why);
    };
    if (target_vertices < 4)
        bad("target_vertices", "must be at least 4 (a tetrahedron), got " + std::to_string(target_vertices));
    if (target_vertices > NeuralMesh::kMaxTargetVertices)
        bad("target_vertices", "must be at most " + std::to_string(NeuralMesh::kMaxTargetVertices) +
                                   " (the mesh holds at most 2^31 half-edges), got " + std::to_string(target_vertices));
    if (!(alpha_w > 0.0 && alpha_w <= 1.0)) bad("alpha_w", "must be in (0, 1], got " + std::to_string(alpha_w));
    if (!(alpha_n >= 0.0 && alpha_n <= 1.0)) bad("alpha_n", "must be in [0, 1], got " + std::to_string(alpha_n));
    if (!(alpha > 0.0 && alpha < 1.0)) bad("alpha", "must be in (0, 1), got " + std::to_string(alpha));
    if (cvs < 1) bad("cvs", "must be at least 1");
    if (cec < 1) bad("cec", "must be at least 1");
    if (!(settle >= 0.0 && settle <= 1e6)) bad("settle", "must be in [0, 1e6], got " + std::to_string(settle));
    if (finish_rounds > 1000) bad("finish_rounds", "must be in [0, 1000], got " + std::to_string(finish_rounds));
    if (fit_rounds > 100) bad("fit_rounds", "must be in [0, 100], got " + std::to_string(fit_rounds));
    if (surface_fit_rounds > 100)
        bad("surface_fit_rounds", "must be in [0, 100], got " + std::to_string(surface_fit_rounds));
    if (exchange_passes > 100) bad("exchange_passes", "must be in [0, 100], got " + std::to_string(exchange_passes));
    if (topology != Topology::sphere && topology != Topology::closed && topology != Topology::open)
        bad("topology", "must be Topology::sphere, closed or open");
    if (fit_rounds > 0 && !finish) bad("fit_rounds", "needs the finishing stage (finish), which is off");
    if (!(adaptivity >= 0.0 && adaptivity <= 100.0))
        bad("adaptivity", "must be in [0, 100], got " + std::to_string(adaptivity));
    if (threads > kMaxThreads)
        bad("threads", "must be in [0, " + std::to_string(kMaxThreads) + "] (0: the machine's cores), got " +
                           std::to_string(threads));
    if (!(min_hole >= 0.0f && min_hole <= 1000.0f)) bad("min_hole", "must be in [0, 1000], got " + std::to_string(min_hole));
    if (!(stray_ratio >= 0.0f && stray_ratio <= 1000.0f))
        bad("stray_ratio", "must be in [0, 1000] (0: keep every point), got " + std::to_string(stray_ratio));
}

}  // namespace nmesh
