#include "nmesh/pipeline/parts.h"

#include <algorithm>
#include <chrono>
#include <numeric>

namespace nmesh::pipeline {

std::vector<std::uint32_t> part_budgets(const CloudParts& parts, std::uint32_t target) {
    const std::uint64_t total = std::accumulate(parts.size.begin(), parts.size.end(), std::uint64_t(0));
    if (parts.size.empty() || total == 0) return {};
    std::vector<std::uint32_t> budget(parts.size.size());
    std::vector<std::pair<std::uint64_t, std::uint32_t>> remainder;  // (remainder, part), largest first
    std::uint64_t given = 0;
    for (std::uint32_t i = 0; i < parts.size.size(); ++i) {
        const std::uint64_t share = std::uint64_t(target) * parts.size[i];
        budget[i] = std::uint32_t(share / total);
        given += budget[i];
        remainder.push_back({share % total, i});
    }
    std::stable_sort(remainder.begin(), remainder.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t k = 0; given < target; ++k, ++given) ++budget[remainder[k].second];
    for (const std::uint32_t b : budget)
        if (b < kMinPartVertices) return {};
    return budget;
}

void add_part_statistics(Statistics& total, const Statistics& part) {
    total.iterations += part.iterations;
    total.settle_iterations += part.settle_iterations;
    total.splits += part.splits;
    total.collapses += part.collapses;
    total.collapses_refused += part.collapses_refused;
    total.removal_passes += part.removal_passes;
    total.swaps_tried += part.swaps_tried;
    total.swaps_kept += part.swaps_kept;
    total.swaps_undone += part.swaps_undone;
    total.swaps_illegal += part.swaps_illegal;
    total.moves_shortened += part.moves_shortened;
    total.folds_undone += part.folds_undone;
    total.side_skips += part.side_skips;
    total.twist_checks += part.twist_checks;
    total.twist_retries += part.twist_retries;
    total.twists_kept += part.twists_kept;
    total.output_retries += part.output_retries;
    total.solid_genus = total.solid_genus >= 0 && part.solid_genus >= 0 ? total.solid_genus + part.solid_genus : -1;
    total.start_core = total.start_core || part.start_core;
    total.start_retries += part.start_retries;
    total.start_vertices += part.start_vertices;
    total.topology_checks += part.topology_checks;
    total.membrane_patches += part.membrane_patches;
    total.handles += part.handles;
    total.membrane_faces_removed += part.membrane_faces_removed;
    total.bridges += part.bridges;
    total.bridge_vertices_removed += part.bridge_vertices_removed;
    total.layer_faces_removed += part.layer_faces_removed;
    total.open_faces_removed += part.open_faces_removed;
    total.crossing_faces_removed += part.crossing_faces_removed;
    total.open_vertices_added += part.open_vertices_added;
    total.indexed_points += part.indexed_points;
    total.index_bytes = std::max(total.index_bytes, part.index_bytes);  // one index at a time
    total.seconds += part.seconds;
    total.seconds_finish += part.seconds_finish;
    total.finished = total.finished && part.finished;
    total.repair_declined = total.repair_declined || part.repair_declined;
    total.seconds_winner += part.seconds_winner;
    total.seconds_update += part.seconds_update;
    total.seconds_split += part.seconds_split;
    total.seconds_collapse += part.seconds_collapse;
    total.seconds_swap += part.seconds_swap;
}

Result reconstruct_parts(PointSpan cloud, const CloudParts& parts, const std::vector<std::uint32_t>& budgets,
                         const Parameters& params, const Callbacks& callbacks, const ReconstructOne& one) {
    std::vector<std::vector<Vec3>> points(parts.count);
    for (std::uint32_t i = 0; i < parts.count; ++i) points[i].reserve(parts.size[i]);
    for (std::size_t i = 0; i < cloud.size(); ++i)
        if (parts.part[i] != kNoPart) points[parts.part[i]].push_back(cloud[i]);
    Result out;
    out.stats.solid_genus = 0;
    out.stats.start_vertices = 0;
    out.stats.finished = true;
    std::uint32_t done = 0;
    double before = 0.0;  // seconds spent on the parts done
    for (std::uint32_t i = 0; i < parts.count; ++i) {
        Parameters p = params;
        p.target_vertices = budgets[i];
        p.stray_ratio = 0.0f;  // read on the whole cloud already
        Callbacks c;
        c.profile = callbacks.profile;
        if (callbacks.progress)
            c.progress = [&callbacks, done, before, target = params.target_vertices](const Progress& progress) {
                Progress q = progress;
                q.vertices += done;
                q.target_vertices = target;
                q.seconds += before;
                q.setup_seconds += before;
                return callbacks.progress(q);
            };
        const auto part_start = std::chrono::steady_clock::now();
        Result r = one(points[i], p, c);
        before += std::chrono::duration<double>(std::chrono::steady_clock::now() - part_start).count();
        const std::uint32_t offset = std::uint32_t(out.mesh.positions.size());
        out.mesh.positions.insert(out.mesh.positions.end(), r.mesh.positions.begin(), r.mesh.positions.end());
        for (const auto& t : r.mesh.triangles)
            out.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        add_part_statistics(out.stats, r.stats);
        done += budgets[i];
        if (r.cancelled) {
            out.cancelled = true;
            break;
        }
    }
    return out;
}

}  // namespace nmesh::pipeline
