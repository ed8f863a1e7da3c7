// nmesh — the command-line tool: reconstruct, eval, info.
//
// Exit status: 0 success, 1 runtime error (one line naming the file and the problem),
// 2 usage error (one line and a hint), 130 interrupted.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/cli/progress_bar.h"
#include "nmesh/cli/render_command.h"
#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "nmesh/reconstruct.h"
#include "nmesh/run_report.h"
#include "nmesh/util/parallel.h"

namespace nmesh::cli {
namespace {

constexpr const char* kMainUsage =
    "usage: nmesh <command> [options]\n"
    "\n"
    "Reconstructs a closed triangle mesh from a point cloud with Neural Meshes ES.\n"
    "\n"
    "commands:\n"
    "  reconstruct INPUT -o OUTPUT [options]   point cloud (PLY, XYZ, OBJ) to mesh (PLY, OBJ, OFF)\n"
    "  eval POINTS MESH [options]              quality of a mesh against its point cloud\n"
    "  info FILE                               what a file holds\n"
    "  render MESH -o IMAGE.png [options]      a picture of a mesh (software rendering, no GPU)\n"
    "\n"
    "Run 'nmesh <command> --help' for the options of a command.\n";

constexpr const char* kReconstructUsage =
    "usage: nmesh reconstruct INPUT -o OUTPUT [options]\n"
    "\n"
    "Learns a mesh of exactly --vertices vertices from the points of INPUT (.ply, .xyz/.txt/.pts,\n"
    ".obj) and writes it to OUTPUT (.ply binary, .obj, .off). Defaults are Table 2 of the\n"
    "Neural Meshes ES paper.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE      the mesh to write (required)\n"
    "  --vertices N           target vertex count (default 10000; the paper's bunny: 30000)\n"
    "  --alpha-w A            winner learning rate, eq. (2) (default 0.08)\n"
    "  --alpha-n A            neighbourhood learning rate, eq. (3) (default 0.01)\n"
    "  --alpha A              signal counter decay per iteration, eq. (7) (default 0.95)\n"
    "  --cvs N                a vertex split every N iterations (default 100)\n"
    "  --cec N                inactive vertices removed every N * n iterations (default 20)\n"
    "  --no-edge-swap         basic Neural Meshes (no edge swap after collapses)\n"
    "  --adaptivity A         a win counts 1 + A * (the winner's distance / its mean)^2, so that\n"
    "                         tips and bends get vertices sooner (closed and open, from the solid's\n"
    "                         start; default 0: the paper's signal counter)\n"
    "  --topology MODE        sphere: genus 0, the paper's algorithm; closed: a closed surface of the\n"
    "                         cloud's genus (its solid's, or handles learnt where it has through-holes);\n"
    "                         open: as closed, then opened where the cloud has no data (default closed)\n"
    "  --min-hole S           open: the smallest hole to open, the distance from its middle to the\n"
    "                         nearest point in local point spacings (default 0: holes several\n"
    "                         spacings deep open, the sampling's gaps and small holes stay closed)\n"
    "  --stray-ratio R        leave out the stray points: those whose 8th nearest neighbour is more\n"
    "                         than R times the cloud's median of that distance away (default 6;\n"
    "                         0 keeps every point)\n"
    "  --no-solid-start       closed and open: grow from a tetrahedron, not from the solid the cloud\n"
    "                         walls round (the handles then come from the handle search)\n"
    "  --no-fold-guard        let step 3 fold the winner's triangles, as the paper's algorithm does\n"
    "  --no-finish            no finishing stage: the learnt mesh as it is (with --no-fold-guard and\n"
    "                         --topology sphere, exactly as the paper's algorithm leaves it)\n"
    "  --finish-rounds N      the finishing stage's regularisation rounds (default 10; 0: repair only)\n"
    "  --fit-rounds N         fit the triangles' centroids to the cloud points N times (default 0):\n"
    "                         lowers DM(X,T) at those points, not the distance to the surface\n"
    "  --surface-fit-rounds N fit the vertices to the cloud's points by least squares, N rounds\n"
    "                         (default 4; 0: off)\n"
    "  --exchange-passes N    move vertices from flat parts to where the surface bends, N passes\n"
    "                         of at most 2% of them each (default 10; 0: where the learning put them)\n"
    "  --index-points K       index at most K cloud points per vertex for the edge swap and the\n"
    "                         finishing stage (default 64; 0: every point)\n"
    "  --settle X             X * n iterations without topology changes at the end (default 0)\n"
    "  --seed S               random seed; the same seed gives the same mesh (default 1)\n"
    "  --threads N            threads for the work beside the learning: the solid's reading, the\n"
    "                         output check, the --stats metrics (default 0: the machine's cores);\n"
    "                         the same mesh for every N\n"
    "  --snapshots N1,N2,...  also write the mesh when it reaches these sizes (OUTPUT_<N>v.ext)\n"
    "  --stats FILE.json      write parameters, statistics and quality metrics as JSON\n"
    "  --ascii                write PLY as ASCII instead of binary\n"
    "  --save-on-interrupt    on Ctrl-C, write the mesh reached so far before exiting\n"
    "  --quiet                no progress and no summary (warnings and errors still shown)\n";

constexpr const char* kEvalUsage =
    "usage: nmesh eval POINTS MESH [--json] [--threads N]\n"
    "\n"
    "Measures MESH against the cloud POINTS: the paper's DM(X,T) (eq. 10-11), point-to-surface and\n"
    "surface-to-point distances, the Hausdorff distance (absolute and relative to the cloud's\n"
    "bounding-box diagonal), topology (closed, manifold, Euler characteristic, genus, components,\n"
    "boundary loops, edges and length, self-intersections) and triangle quality.\n"
    "\n"
    "options:\n"
    "  --json                 print JSON instead of text\n"
    "  --threads N            threads for the measuring (default 0: the machine's cores); the same\n"
    "                         report for every N\n";

constexpr const char* kInfoUsage =
    "usage: nmesh info FILE\n"
    "\n"
    "Prints the format, the element counts and the bounding box of a point or mesh file; for a mesh\n"
    "also its topology: components, closed, manifold, boundary loops, Euler characteristic, genus.\n";

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) { g_interrupted.store(true); }

bool wants_help(int argc, char** argv) {
    for (int i = 2; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
    return false;
}

// Whether two paths name the same file, however they are spelled (./x, an absolute path, a
// hard link), so that no output can replace the input or another output.
bool same_file(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    std::error_code ea, eb, eq;
    const fs::path pa = fs::weakly_canonical(a, ea), pb = fs::weakly_canonical(b, eb);
    if (!ea && !eb && pa == pb) return true;
    return fs::equivalent(a, b, eq);
}

std::string snapshot_path(const std::string& output, std::uint32_t n) {
    const auto slash = output.find_last_of('/');
    const auto dot = output.find_last_of('.');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    const std::string stem = has_ext ? output.substr(0, dot) : output;
    const std::string ext = has_ext ? output.substr(dot) : "";
    return stem + "_" + std::to_string(n) + "v" + ext;
}

void print_summary(const Result& r, const std::string& output) {
    const Statistics& s = r.stats;
    char finishing_text[64] = "";
    if (s.finished) std::snprintf(finishing_text, sizeof finishing_text, ", %.2f s finishing", s.seconds_finish);
    const std::string finishing = finishing_text;
    std::fprintf(stderr,
                 "nmesh: wrote %s: %zu vertices, %zu faces\n"
                 "nmesh: %llu iterations, %llu splits, %llu collapses (%llu refused), "
                 "%llu swaps kept of %llu tried, %.2f s learning (%.1f M it/s)%s\n",
                 output.c_str(), r.mesh.positions.size(), r.mesh.triangles.size(), (unsigned long long)s.iterations,
                 (unsigned long long)s.splits, (unsigned long long)s.collapses, (unsigned long long)s.collapses_refused,
                 (unsigned long long)s.swaps_kept, (unsigned long long)s.swaps_tried, s.seconds,
                 s.seconds > 0 ? s.iterations / s.seconds / 1e6 : 0.0, finishing.c_str());
    if (s.parts_apart)
        std::fprintf(stderr,
                     "nmesh: genus %d, %llu boundary loops, in %u closed surfaces (the cloud's parts far "
                     "apart, a surface each; %llu handles learnt)\n",
                     s.genus, (unsigned long long)s.boundary_loops, s.cloud_parts, (unsigned long long)s.handles);
    else if (s.start_core)
        std::fprintf(stderr, "nmesh: genus %d, %llu boundary loops (learnt from the genus-0 core of the cloud's solid, "
                     "whose genus did not hold; %llu handles learnt)\n",
                     s.genus, (unsigned long long)s.boundary_loops, (unsigned long long)s.handles);
    else if (s.start_vertices > 4)
        std::fprintf(stderr, "nmesh: genus %d, %llu boundary loops (learnt from the surface of the cloud's solid, genus %d)\n",
                     s.genus, (unsigned long long)s.boundary_loops, s.solid_genus);
    else
        std::fprintf(stderr, "nmesh: genus %d, %llu boundary loops (%llu handles learnt)\n", s.genus,
                     (unsigned long long)s.boundary_loops, (unsigned long long)s.handles);
    if (s.cloud_parts > 1 && !s.parts_apart)
        std::fprintf(stderr,
                     "nmesh: warning: the cloud is in %u parts far apart, too many for %zu vertices to give "
                     "each its own surface: the closed surface joins them\n",
                     s.cloud_parts, r.mesh.positions.size());
    if (s.stray_points > 0)
        std::fprintf(stderr,
                     "nmesh: left out %llu stray points, far from the others (--stray-ratio 0 keeps them)\n",
                     (unsigned long long)s.stray_points);
    if (s.twist_retries > 0 || s.output_retries > 0)
        std::fprintf(stderr,
                     "nmesh: learnt again from a checkpoint: %llu retries where part of the mesh had turned "
                     "inside out, %llu where the output was not valid (the counts above are the kept path's)\n",
                     (unsigned long long)s.twist_retries, (unsigned long long)s.output_retries);
}

// evaluate(), with its progress on stderr when it takes long (a cloud of millions of points).
QualityReport evaluate_with_progress(const std::vector<Vec3>& points, const IndexedMesh& mesh, bool quiet,
                                     std::uint32_t threads) {
    ProgressBar bar(ProgressBar::detect(quiet));
    EvalOptions options;
    options.progress = bar.task("measuring the mesh against the cloud");
    options.threads = threads;
    const QualityReport q = evaluate(points, mesh, options);
    bar.finish();
    return q;
}

int run_reconstruct(int argc, char** argv) {
    if (wants_help(argc, argv)) {
        std::fputs(kReconstructUsage, stdout);
        return 0;
    }
    const Arguments args(
        argc, argv, 2,
        {"--no-edge-swap", "--no-fold-guard", "--no-solid-start", "--no-finish", "--quiet", "--ascii", "--save-on-interrupt"},
        {"-o", "--output", "--vertices", "--alpha-w", "--alpha-n", "--alpha", "--cvs", "--cec", "--seed", "--snapshots",
         "--stats", "--settle", "--finish-rounds", "--fit-rounds", "--surface-fit-rounds", "--exchange-passes",
         "--index-points",
         "--topology", "--min-hole", "--stray-ratio", "--adaptivity", "--threads"});
    if (args.positional().size() != 1) throw UsageError("reconstruct takes one INPUT file");
    const std::string input = args.positional()[0];
    const std::string output = args.has("-o") ? args.text("-o") : args.text("--output");
    if (output.empty()) throw UsageError("reconstruct needs an output file: -o OUTPUT");
    if (same_file(output, input)) throw UsageError("the output file must not be the input file");
    const std::string stats_path = args.text("--stats");
    if (!stats_path.empty() && (same_file(stats_path, input) || same_file(stats_path, output)))
        throw UsageError("the --stats file must not be the input or the output file");
    std::vector<std::uint32_t> snapshots;
    for (std::uint64_t n : args.count_list("--snapshots")) {
        const std::string path = snapshot_path(output, std::uint32_t(n));
        if (n > 0xffffffffull || same_file(path, input) || (!stats_path.empty() && same_file(path, stats_path)))
            throw UsageError("--snapshots " + std::to_string(n) + " would write " + path +
                             ", which is the input or the --stats file");
        snapshots.push_back(std::uint32_t(n));
    }
    // Outputs that cannot be written are errors now, not after the learning.
    check_mesh_output(output);
    if (!stats_path.empty()) check_output_location(stats_path);
    for (std::uint32_t n : snapshots) check_mesh_output(snapshot_path(output, n));

    Parameters p;
    auto bounded_count = [&](const char* name, std::uint64_t fallback) {
        const std::uint64_t v = args.count(name, fallback);
        if (v > 0xffffffffull) throw UsageError(std::string("option ") + name + " is too large");
        return std::uint32_t(v);
    };
    p.target_vertices = bounded_count("--vertices", p.target_vertices);
    p.alpha_w = args.number("--alpha-w", p.alpha_w);
    p.alpha_n = args.number("--alpha-n", p.alpha_n);
    p.alpha = args.number("--alpha", p.alpha);
    p.cvs = bounded_count("--cvs", p.cvs);
    p.cec = bounded_count("--cec", p.cec);
    p.settle = args.number("--settle", p.settle);
    p.min_hole = float(args.number("--min-hole", p.min_hole));
    p.stray_ratio = float(args.number("--stray-ratio", p.stray_ratio));
    p.adaptivity = args.number("--adaptivity", p.adaptivity);
    p.seed = args.count("--seed", p.seed);
    p.edge_swap = !args.has("--no-edge-swap");
    p.fold_guard = !args.has("--no-fold-guard");
    p.solid_start = !args.has("--no-solid-start");
    p.finish = !args.has("--no-finish");
    p.finish_rounds = bounded_count("--finish-rounds", p.finish_rounds);
    p.fit_rounds = bounded_count("--fit-rounds", p.fit_rounds);
    p.surface_fit_rounds = bounded_count("--surface-fit-rounds", p.surface_fit_rounds);
    p.exchange_passes = bounded_count("--exchange-passes", p.exchange_passes);
    p.index_points_per_vertex = bounded_count("--index-points", p.index_points_per_vertex);
    p.threads = bounded_count("--threads", p.threads);
    try {
        if (args.has("--topology")) p.topology = parse_topology(args.text("--topology").c_str());
        p.validate();
    } catch (const ParameterError& e) {
        throw UsageError(e.what());
    }
    const bool quiet = args.has("--quiet");
    MeshWriteOptions write_options;
    write_options.ply_ascii = args.has("--ascii");

    PointReadReport read_report;
    const PointCloud cloud = read_points(input, &read_report);
    if (!quiet)
        std::fprintf(stderr, "nmesh: read %s: %llu points (%s)\n", input.c_str(),
                     (unsigned long long)read_report.points_read, read_report.format.c_str());
    // Warnings are printed even with --quiet, which silences only progress and summaries.
    if (read_report.non_finite_dropped)
        std::fprintf(stderr, "nmesh: warning: %s: dropped %llu points with NaN or infinite coordinates\n",
                     input.c_str(), (unsigned long long)read_report.non_finite_dropped);

    ProgressBar bar(ProgressBar::detect(quiet));
    Callbacks cb;
    cb.progress = bar.reconstruction(g_interrupted);
    cb.snapshot_vertices = snapshots;
    cb.on_snapshot = [&](std::uint32_t n, const IndexedMesh& m) {
        write_mesh(snapshot_path(output, n), m, write_options);
    };
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    Result r;
    try {
        r = reconstruct(cloud, p, cb);
    } catch (const InputError& e) {
        throw IoError(input, e.what());
    }
    bar.finish();
    if (r.cancelled) {
        if (!args.has("--save-on-interrupt")) {
            std::fprintf(stderr, "nmesh: interrupted after %llu iterations; nothing written\n",
                         (unsigned long long)r.stats.iterations);
            return 130;
        }
        write_mesh(output, r.mesh, write_options);
        std::fprintf(stderr, "nmesh: interrupted; wrote the mesh reached so far (%zu vertices) to %s\n",
                     r.mesh.positions.size(), output.c_str());
        return 130;
    }
    write_mesh(output, r.mesh, write_options);
    // Topology open takes the vertices inside the holes away: said, since the count was asked for.
    if (r.mesh.positions.size() < p.target_vertices)
        std::fprintf(stderr,
                     "nmesh: note: %s has %zu vertices, %llu fewer than asked: the surface was opened where the "
                     "cloud has no data\n",
                     output.c_str(), r.mesh.positions.size(),
                     (unsigned long long)(p.target_vertices - r.mesh.positions.size()));
    // One line; when the repair declined the mesh, it says why and what to try.
    if (r.stats.crossing_pairs > 0 || r.stats.inward_faces > 0)
        std::fprintf(stderr, "nmesh: warning: %s is not a valid surface: %llu pairs of crossing triangles, %llu faces "
                     "pointing inward%s\n",
                     output.c_str(), (unsigned long long)r.stats.crossing_pairs,
                     (unsigned long long)r.stats.inward_faces,
                     r.stats.repair_declined ? " (too many for the finishing stage to repair: a scan seen from one "
                                               "side? try --topology open)"
                                             : "");
    if (args.has("--stats")) {
        const QualityReport q = evaluate_with_progress(cloud.points, r.mesh, quiet, p.threads);
        write_file_atomically(stats_path, [&](std::ostream& o) { write_run_json(o, input, p, r, q); });
        if (!quiet)
            std::fprintf(stderr, "nmesh: DM(X,T) %.6g, Hausdorff %.3g%% of the diagonal; wrote %s\n", q.dm_x_t,
                         100.0 * q.hausdorff_rel, stats_path.c_str());
    }
    if (!quiet) print_summary(r, output);
    return 0;
}

int run_eval(int argc, char** argv) {
    if (wants_help(argc, argv)) {
        std::fputs(kEvalUsage, stdout);
        return 0;
    }
    const Arguments args(argc, argv, 2, {"--json"}, {"--threads"});
    if (args.positional().size() != 2) throw UsageError("eval takes two files: POINTS MESH");
    const std::uint64_t threads = args.count("--threads", 0);
    if (threads > kMaxThreads)
        throw UsageError("invalid option --threads: must be in [0, " + std::to_string(kMaxThreads) + "], got " +
                         std::to_string(threads));
    const PointCloud cloud = read_points(args.positional()[0]);
    const IndexedMesh mesh = read_mesh(args.positional()[1]);
    if (cloud.empty()) throw IoError(args.positional()[0], "no points");
    const QualityReport q = evaluate_with_progress(cloud.points, mesh, false, std::uint32_t(threads));
    if (args.has("--json")) {
        write_json(std::cout, q);
        std::cout << "\n";
    } else {
        write_text(std::cout, q);
    }
    return 0;
}

// The topology lines of `nmesh info`.
void print_topology(const MeshTopology& t) {
    const auto yes_no = [](bool b) { return b ? "yes" : "no"; };
    std::printf("components: %zu\nclosed: %s\nmanifold: %s\n", t.components, yes_no(t.closed), yes_no(t.manifold));
    if (t.boundary_edges == 0)
        std::printf("boundary loops: 0\n");
    else
        std::printf("boundary loops: %zu (%zu edges, length %g)\n", t.boundary_loops, t.boundary_edges,
                    t.boundary_length);
    if (t.isolated_vertices) std::printf("vertices in no face: %zu\n", t.isolated_vertices);
    std::printf("euler characteristic: %lld\n", t.euler);
    if (t.genus >= 0)
        std::printf("genus: %d\n", t.genus);
    else
        std::printf("genus: - (not a manifold)\n");
}

int run_info(int argc, char** argv) {
    if (wants_help(argc, argv)) {
        std::fputs(kInfoUsage, stdout);
        return 0;
    }
    const Arguments args(argc, argv, 2, {}, {});
    if (args.positional().size() != 1) throw UsageError("info takes one FILE");
    const std::string path = args.positional()[0];
    const FileInfo info = inspect_file(path);
    std::printf("file: %s\nformat: %s (%s)\nsize: %llu bytes\n", path.c_str(), info.format.c_str(),
                info.encoding.c_str(), (unsigned long long)info.file_size);
    for (const PlyElementInfo& e : info.elements) {
        std::printf("element %s: %llu\n", e.name.c_str(), (unsigned long long)e.count);
        for (const std::string& prop : e.properties) std::printf("  property %s\n", prop.c_str());
    }
    std::printf("points: %llu\n", (unsigned long long)info.points);
    if (info.non_finite)
        std::printf("points with NaN or infinite coordinates: %llu\n", (unsigned long long)info.non_finite);
    std::printf("faces: %llu\n", (unsigned long long)info.faces);
    if (!info.bounds.empty()) {
        std::printf("bounding box: [%g, %g, %g] to [%g, %g, %g]\ndiagonal: %g\n", info.bounds.min.x, info.bounds.min.y,
                    info.bounds.min.z, info.bounds.max.x, info.bounds.max.y, info.bounds.max.z, info.bounds.diagonal());
    }
    if (!info.topology_error.empty()) std::printf("topology: not computed: %s\n", info.topology_error.c_str());
    if (info.topology) print_topology(*info.topology);
    return 0;
}

}  // namespace
}  // namespace nmesh::cli

int main(int argc, char** argv) {
    using namespace nmesh::cli;
    const std::string command = argc > 1 ? argv[1] : "";
    const char* hint = "run 'nmesh --help' for usage";
    try {
        if (command == "reconstruct") {
            hint = "run 'nmesh reconstruct --help' for usage";
            return run_reconstruct(argc, argv);
        }
        if (command == "eval") {
            hint = "run 'nmesh eval --help' for usage";
            return run_eval(argc, argv);
        }
        if (command == "info") {
            hint = "run 'nmesh info --help' for usage";
            return run_info(argc, argv);
        }
        if (command == "render") {
            hint = "run 'nmesh render --help' for usage";
            return run_render(argc, argv);
        }
        if (command == "--help" || command == "-h" || command == "help") {
            std::fputs(kMainUsage, stdout);
            return 0;
        }
        if (command.empty()) throw UsageError("no command given");
        throw UsageError("unknown command '" + command + "'");
    } catch (const UsageError& e) {
        std::fprintf(stderr, "nmesh: %s (%s)\n", e.what(), hint);
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "nmesh: error: %s\n", e.what());
        return 1;
    }
}
