// Benchmark of the pipeline stage by stage: what reading the cloud, the solid's reading, the
// cloud's index, the learning, the finishing stage, the output check, writing the mesh and the
// metrics (--stats, `nmesh eval`) each take, as medians over runs.
//
//     bench_stages CLOUD [--vertices N] [--runs R] [--threads T] [--topology MODE] [--no-metrics]
//                  [--write MESH.ply]
//
// The learning and the finishing stage are timed inside reconstruct() (Statistics::seconds less
// the setup, and seconds_finish); the setup, the solid's reading, the index, the output check
// and the metrics are run again on their own, on the same input, so that each has its own time:
// "setup" is reconstruct()'s time before the first iteration (normalising, the solid's reading,
// the index, the samples' sides), of which "solid" and "index" are the two measured parts.
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/metrics.h"
#include "nmesh/pipeline/normalization.h"
#include "nmesh/pipeline/output_check.h"
#include "nmesh/reconstruct.h"
#include "nmesh/spatial/cloud_sample.h"
#include "summary.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_of(const std::function<void()>& f) {
    const auto t0 = Clock::now();
    f();
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: %s CLOUD [--vertices N] [--runs R] [--threads T] [--topology MODE] [--no-metrics]\n"
                     "       [--write MESH.ply]\n",
                     argv[0]);
        return 2;
    }
    nmesh::Parameters params;
    int runs = 5;
    bool metrics = true;
    std::string write_path;
    try {
        const nmesh::cli::Arguments args(argc, argv, 2, {"--no-metrics"},
                                         {"--vertices", "--runs", "--threads", "--topology", "--write"});
        params.target_vertices = std::uint32_t(args.count("--vertices", 30000));
        runs = int(std::max<std::uint64_t>(1, args.count("--runs", 5)));
        params.threads = std::uint32_t(args.count("--threads", 0));
        if (args.has("--topology")) params.topology = nmesh::parse_topology(args.text("--topology").c_str());
        metrics = !args.has("--no-metrics");
        write_path = args.text("--write");
        params.validate();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 2;
    }
    try {
        const char* names[] = {"read",   "setup",  "solid",   "index",   "learning",
                               "finish", "check",  "write",   "metrics", "reconstruct()"};
        constexpr int kStages = int(sizeof names / sizeof names[0]);
        std::vector<double> t[kStages];
        nmesh::PointCloud cloud;
        auto span = [&] { return nmesh::PointSpan(cloud.points); };
        for (int r = 0; r < runs; ++r) {
            t[0].push_back(seconds_of([&] { cloud = nmesh::read_points(argv[1]); }));
            const nmesh::pipeline::Normalization norm(nmesh::pipeline::require_reconstructible(span()));
            if (params.topology != nmesh::Topology::sphere && params.solid_start)
                t[2].push_back(seconds_of([&] {
                    nmesh::solid_start(span(), norm.transform, params.target_vertices, params.threads);
                }));
            t[3].push_back(seconds_of([&] { nmesh::index_cloud(span(), norm.transform, norm.bounds, params); }));
            double setup = 0.0;
            nmesh::Callbacks callbacks;
            callbacks.progress = [&](const nmesh::Progress& p) {
                setup = p.setup_seconds;
                return true;
            };
            nmesh::Result result;
            t[9].push_back(seconds_of([&] { result = nmesh::reconstruct(cloud, params, callbacks); }));
            t[1].push_back(setup);
            t[4].push_back(result.stats.seconds - setup);
            t[5].push_back(result.stats.seconds_finish);
            nmesh::Result again = result;
            t[6].push_back(seconds_of([&] { nmesh::pipeline::check_output(again, params.threads); }));
            if (!write_path.empty())
                t[7].push_back(seconds_of([&] { nmesh::write_mesh(write_path, result.mesh); }));
            if (metrics) {
                nmesh::EvalOptions options;
                options.threads = params.threads;
                t[8].push_back(seconds_of([&] { nmesh::evaluate(span(), result.mesh, options); }));
            }
        }
        std::printf("cloud %s: %zu points -> %u vertices, topology %s, threads %u, %d runs (medians, min-max)\n",
                    argv[1], cloud.size(), params.target_vertices, nmesh::topology_name(params.topology),
                    params.threads, runs);
        for (int s = 0; s < kStages; ++s) {
            if (t[s].empty()) continue;
            const nmesh::bench::Summary m = nmesh::bench::summarize(t[s]);
            std::printf("  %-14s %8.3f s  (%.3f-%.3f)\n", names[s], m.median, m.min, m.max);
        }
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
