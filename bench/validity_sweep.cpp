// bench/validity_sweep.cpp — every cloud x seed x size, with and without the finishing stage: is
// each output a valid surface? Per run: the crossing triangle pairs (the exact test), the signed
// volume, the share of faces pointing inward, the genus, boundary loops and components, the
// Hausdorff distance and the time. Writes one CSV row per run and a markdown summary per cloud,
// size and stage setting.
//
//   validity_sweep CLOUD... --csv OUT.csv --md OUT.md [--seeds 1-20] [--sizes 1000,3000,5000,10000,30000]
//                  [--finish both|on|off] [--topology sphere|closed|open] [--check] [--exempt NAME,...]
//
// A size is run on a cloud only when the cloud has at least 1.1 points per vertex (fewer cannot
// carry it with the paper's parameters: the mesh stops growing). --check exits with status 1 if
// any run, except on the clouds named by --exempt, has crossing pairs or inward faces.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/reconstruct.h"
#include "number_list.h"
#include "summary.h"

namespace {

struct Run {
    std::string cloud;
    std::uint32_t vertices = 0;
    std::uint64_t seed = 0;
    bool finish = false;
    std::string error;  // the library's error when the run failed
    std::size_t crossing_pairs = 0;
    double volume = 0.0;
    double inward_share = 0.0;
    std::size_t inward_patch = 0;  // faces in the largest edge-connected patch of inward faces
    double hausdorff_rel = 0.0;
    double seconds_learning = 0.0, seconds_finish = 0.0;
    bool closed = false;
    int genus = -1;
    std::size_t boundary_loops = 0, components = 0;
};

std::string name_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

nmesh::Topology g_topology = nmesh::Parameters{}.topology;  // --topology, for every run

Run run_one(const std::string& name, const nmesh::PointCloud& cloud, std::uint32_t vertices, std::uint64_t seed,
            bool finish) {
    Run r;
    r.cloud = name;
    r.vertices = vertices;
    r.seed = seed;
    r.finish = finish;
    nmesh::Parameters p;
    p.target_vertices = vertices;
    p.seed = seed;
    p.finish = finish;
    p.topology = g_topology;
    try {
        const nmesh::Result res = nmesh::reconstruct(cloud, p);
        nmesh::EvalOptions o;
        o.surface_samples = 50000;
        const nmesh::QualityReport q = nmesh::evaluate(cloud.points, res.mesh, o);
        r.crossing_pairs = q.self_intersections;
        r.volume = q.signed_volume;
        r.inward_share = q.faces > 0 ? double(q.inward_faces) / double(q.faces) : 0.0;
        if (q.inward_faces > 0) {
            const nmesh::TriangleBvh bvh(res.mesh);
            const auto inward = nmesh::inward_face_flags(res.mesh, bvh);
            r.inward_patch = nmesh::largest_patch(res.mesh, inward);
        }
        r.hausdorff_rel = q.hausdorff_rel;
        r.seconds_learning = res.stats.seconds;
        r.seconds_finish = res.stats.seconds_finish;
        r.closed = q.closed;
        r.genus = q.genus;
        r.boundary_loops = q.boundary_loops;
        r.components = q.components;
    } catch (const nmesh::Error& e) {
        r.error = e.what();
    }
    return r;
}

bool defective(const Run& r) { return !r.error.empty() || r.crossing_pairs > 0 || r.inward_share > 0.0; }

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> clouds;
    std::vector<std::uint64_t> seeds, sizes;
    std::string csv, md, finish_mode;
    std::vector<std::string> exempt;
    bool check = false;
    try {
        const nmesh::cli::Arguments args(argc, argv, 1, {"--check"},
                                         {"--csv", "--md", "--seeds", "--sizes", "--finish", "--exempt", "--topology"});
        clouds = args.positional();
        seeds = nmesh::bench::parse_range(args.text("--seeds", "1-20"));
        sizes = nmesh::bench::parse_range(args.text("--sizes", "1000,3000,5000,10000,30000"));
        finish_mode = args.text("--finish", "both");
        if (args.has("--topology")) g_topology = nmesh::parse_topology(args.text("--topology").c_str());
        csv = args.text("--csv");
        md = args.text("--md");
        check = args.has("--check");
        std::stringstream ex(args.text("--exempt"));
        for (std::string s; std::getline(ex, s, ',');) exempt.push_back(s);
        if (clouds.empty() || csv.empty() || md.empty() ||
            (finish_mode != "both" && finish_mode != "on" && finish_mode != "off"))
            throw nmesh::cli::UsageError("give clouds, --csv and --md; --finish is both, on or off");
    } catch (const std::exception& e) {
        std::fprintf(stderr,
                     "%s\nusage: %s CLOUD... --csv OUT.csv --md OUT.md [--seeds 1-20] "
                     "[--sizes 1000,3000,5000,10000,30000] [--finish both|on|off] [--check] [--exempt NAME,...]\n",
                     e.what(), argv[0]);
        return 2;
    }
    std::vector<bool> finishes;
    if (finish_mode != "off") finishes.push_back(true);
    if (finish_mode != "on") finishes.push_back(false);

    std::vector<Run> runs;
    const auto start = std::chrono::steady_clock::now();
    try {
        for (const std::string& path : clouds) {
            const nmesh::PointCloud cloud = nmesh::read_points(path);
            const std::string name = name_of(path);
            for (const std::uint64_t n : sizes) {
                if (double(cloud.size()) < 1.1 * double(n)) continue;
                for (const bool finish : finishes)
                    for (const std::uint64_t seed : seeds) {
                        runs.push_back(run_one(name, cloud, std::uint32_t(n), seed, finish));
                        const Run& r = runs.back();
                        std::fprintf(stderr,
                                     "%s %u seed %llu %s: %zu crossing pairs, inward %.4f%%, Hausdorff %.2f%%%s%s\n",
                                     name.c_str(), r.vertices, (unsigned long long)r.seed,
                                     finish ? "finished" : "learnt", r.crossing_pairs, 100.0 * r.inward_share,
                                     100.0 * r.hausdorff_rel, r.error.empty() ? "" : ", error: ", r.error.c_str());
                    }
            }
        }
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    {
        std::ofstream out(csv);
        out << "cloud,vertices,seed,finish,crossing_pairs,signed_volume,inward_share,inward_patch,hausdorff_rel,closed,"
               "genus,boundary_loops,components,seconds_learning,seconds_finish,error\n";
        out.precision(6);
        for (const Run& r : runs)
            out << r.cloud << ',' << r.vertices << ',' << r.seed << ',' << (r.finish ? 1 : 0) << ',' << r.crossing_pairs
                << ',' << r.volume << ',' << r.inward_share << ',' << r.inward_patch << ',' << r.hausdorff_rel << ','
                << (r.closed ? 1 : 0) << ',' << r.genus << ',' << r.boundary_loops << ',' << r.components << ','
                << r.seconds_learning << ','
                << r.seconds_finish << ",\"" << r.error << "\"\n";
    }
    // Summary per cloud, size and stage setting, in the order run.
    std::vector<std::tuple<std::string, std::uint32_t, bool>> keys;
    std::map<std::tuple<std::string, std::uint32_t, bool>, std::vector<const Run*>> groups;
    for (const Run& r : runs) {
        const auto key = std::make_tuple(r.cloud, r.vertices, r.finish);
        if (groups[key].empty()) keys.push_back(key);
        groups[key].push_back(&r);
    }
    std::ofstream out(md);
    out << "# Validity sweep (topology " << nmesh::topology_name(g_topology)
        << ")\n\nEach row: one cloud and size, with the finishing stage (`finished`) or without it "
           "(`learnt`), over the seeds. Crossing pairs by the exact test; a face points inward when the point just "
           "off it along its normal has a nonzero winding number, and the largest inward patch is the most faces "
           "in one edge-connected patch of them (a fold turns a few triangles over, a twist a whole region); "
           "Hausdorff distance in % of the cloud's bounding-box diagonal; the largest ratio of the finishing "
           "stage's time to the learning's.\n\n";
    out << "| cloud | vertices | stage | runs | with crossings | most pairs | with inward faces | most inward | "
           "largest inward patch | "
           "negative volume | genus (runs) | with boundary | most loops | most components | Hausdorff median | max | "
           "max / median | finish / learning (max) | errors |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    bool failed = false;
    char buf[512];
    for (const auto& key : keys) {
        const auto& g = groups[key];
        std::size_t crossing = 0, most = 0, inward = 0, negative = 0, errors = 0;
        std::size_t bounded = 0, most_loops = 0, most_components = 0;
        std::size_t largest_patch = 0;
        double most_inward = 0.0, finish_ratio = 0.0;
        std::vector<double> h;
        std::map<int, int> genera;  // genus -> runs
        for (const Run* r : g) {
            if (!r->error.empty()) {
                ++errors;
                continue;
            }
            crossing += r->crossing_pairs > 0;
            most = std::max(most, r->crossing_pairs);
            inward += r->inward_share > 0.0;
            most_inward = std::max(most_inward, r->inward_share);
            largest_patch = std::max(largest_patch, r->inward_patch);
            negative += r->volume < 0.0;
            ++genera[r->genus];
            bounded += r->boundary_loops > 0;
            most_loops = std::max(most_loops, r->boundary_loops);
            most_components = std::max(most_components, r->components);
            h.push_back(100.0 * r->hausdorff_rel);
            if (r->seconds_learning > 0.0)
                finish_ratio = std::max(finish_ratio, r->seconds_finish / r->seconds_learning);
            if (defective(*r) && std::find(exempt.begin(), exempt.end(), r->cloud) == exempt.end()) failed = true;
        }
        const nmesh::bench::Summary s = h.empty() ? nmesh::bench::Summary{} : nmesh::bench::summarize(h);
        std::string genus_text;  // "0 (10)" or "1 (7), 0 (3)"
        for (auto it = genera.rbegin(); it != genera.rend(); ++it)
            genus_text +=
                (genus_text.empty() ? "" : ", ") + std::to_string(it->first) + " (" + std::to_string(it->second) + ")";
        std::snprintf(buf, sizeof buf,
                      "| %s | %u | %s | %zu | %zu | %zu | %zu | %.2f%% | %zu | %zu | %s | %zu | %zu | %zu "
                      "| %.2f%% | %.2f%% | %.2f | %.2f | %zu |\n",
                      std::get<0>(key).c_str(), std::get<1>(key), std::get<2>(key) ? "finished" : "learnt", g.size(),
                      crossing, most, inward, 100.0 * most_inward, largest_patch, negative, genus_text.c_str(), bounded,
                      most_loops, most_components, s.median, s.max, s.median > 0.0 ? s.max / s.median : 0.0,
                      finish_ratio, errors);
        out << buf;
    }
    std::snprintf(buf, sizeof buf, "\n%zu runs in %.0f s.\n", runs.size(), seconds);
    out << buf;
    std::fprintf(stderr, "%zu runs in %.0f s; summary in %s, runs in %s\n", runs.size(), seconds, md.c_str(),
                 csv.c_str());
    if (check && failed) {
        std::fprintf(stderr, "FAILED: some runs have crossing triangles, inward faces or errors (see %s)\n",
                     md.c_str());
        return 1;
    }
    return 0;
}
