// Benchmark of the learning loop: reconstructs a cloud several times and reports the median,
// minimum and maximum wall time (learning only, file I/O excluded), iterations per second, and
// in a separate profiled run the share of time in each phase.
//
//     bench_reconstruct CLOUD.ply [--vertices N] [--runs R] [--no-edge-swap] [--csv FILE]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/reconstruct.h"
#include "summary.h"

namespace {

using nmesh::bench::summarize;
using nmesh::bench::Summary;

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: %s CLOUD [--vertices N] [--runs R] [--no-edge-swap] [--topology MODE] [--csv FILE]\n",
                     argv[0]);
        return 2;
    }
    nmesh::Parameters params;
    int runs = 5;
    std::string csv;
    try {
        const nmesh::cli::Arguments args(argc, argv, 2, {"--no-edge-swap"},
                                         {"--vertices", "--runs", "--csv", "--topology"});
        params.target_vertices = std::uint32_t(args.count("--vertices", 30000));
        runs = int(std::max<std::uint64_t>(1, args.count("--runs", 5)));
        params.edge_swap = !args.has("--no-edge-swap");
        if (args.has("--topology")) params.topology = nmesh::parse_topology(args.text("--topology").c_str());
        csv = args.text("--csv");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 2;
    }
    try {
        const nmesh::PointCloud cloud = nmesh::read_points(argv[1]);
        std::vector<double> seconds, rates, finishing;
        nmesh::Statistics last;
        for (int r = 0; r < runs; ++r) {
            const nmesh::Result res = nmesh::reconstruct(cloud, params);
            seconds.push_back(res.stats.seconds);
            finishing.push_back(res.stats.seconds_finish);
            rates.push_back(double(res.stats.iterations) / res.stats.seconds);
            last = res.stats;
        }
        nmesh::Callbacks profiled;
        profiled.profile = true;
        const nmesh::Statistics p = nmesh::reconstruct(cloud, params, profiled).stats;
        const Summary t = summarize(seconds), it = summarize(rates), fin = summarize(finishing);
        const double total =
            p.seconds_winner + p.seconds_update + p.seconds_split + p.seconds_collapse + p.seconds_swap;
        auto share = [&](double s) { return total > 0 ? 100.0 * s / total : 0.0; };
        std::printf("cloud %s: %zu points -> %u vertices, edge swap %s, topology %s, %d runs\n", argv[1], cloud.size(),
                    params.target_vertices, params.edge_swap ? "on" : "off", nmesh::topology_name(params.topology),
                    runs);
        std::printf("time      median %.3f s  min %.3f s  max %.3f s  (learning, steps 1-9)\n", t.median, t.min, t.max);
        std::printf(
            "finishing median %.3f s  min %.3f s  max %.3f s  (the stage after learning, not in the time above)\n",
            fin.median, fin.min, fin.max);
        std::printf("rate      median %.2f M it/s  min %.2f  max %.2f  (%llu iterations)\n", it.median / 1e6,
                    it.min / 1e6, it.max / 1e6, (unsigned long long)last.iterations);
        std::printf(
            "phases    winner search %.1f%%  move+smooth+counters %.1f%%  split %.1f%%  collapse %.1f%%  swap %.1f%%"
            "  (profiled run: %.3f s)\n",
            share(p.seconds_winner), share(p.seconds_update), share(p.seconds_split), share(p.seconds_collapse),
            share(p.seconds_swap), p.seconds);
        if (!csv.empty()) {
            std::FILE* f = std::fopen(csv.c_str(), "a");
            if (!f) throw nmesh::IoError(csv, "cannot open for appending");
            std::fprintf(f, "%zu,%u,%d,%s,%d,%.4f,%.4f,%.4f,%.0f,%.1f,%.1f,%.1f,%.1f,%.1f,%.4f\n", cloud.size(),
                         params.target_vertices, params.edge_swap ? 1 : 0, nmesh::topology_name(params.topology), runs,
                         t.median, t.min, t.max, it.median, share(p.seconds_winner), share(p.seconds_update),
                         share(p.seconds_split), share(p.seconds_collapse), share(p.seconds_swap), fin.median);
            std::fclose(f);
        }
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
