// bench/corpus_sweep.cpp — every cloud against its reference mesh: does the method hold on shapes
// it was not tuned to? For each cloud NAME.ply with a reference NAME_mesh.ply beside it (the
// source surface of a sampled cloud, the range-grid triangulation of a scan), at sizes given as
// fractions of the cloud's point count, over seeds: the genus against the reference's, the
// Hausdorff distance to the cloud against the reference's own (the floor any reconstruction
// meets), the distance to the reference surface both ways, crossing pairs, inward faces, boundary
// loops, components, the largest piece's share of the area, the area against the reference's,
// the vertex count and the time. One CSV row per run, one markdown table row per cloud and size.
//
//   corpus_sweep CLOUD... --csv OUT.csv --md OUT.md [--seeds 1-10] [--fractions 2,6]
//                [--sizes N,...] [--topology closed|open|sphere] [--check] [--samples N]
//                [--genus NAME=G,...] [--surface-fit-rounds N]
//
// --fractions 2,6: points / 2 and points / 6 vertices; --sizes: these vertex counts instead. A
// goal failure: a run in topology closed of a cloud whose reference is a manifold (closed, or with
// the scanner's holes, as the bunny's) with crossing pairs, inward faces, an error or a genus other
// than the reference's. --check exits with 1 when a run has an error or crossing pairs, or, in
// topology closed, inward faces or a genus above the reference's. Distances are in % of the
// cloud's bounding-box diagonal; the distance to the reference is measured from samples drawn
// uniformly by area on each surface (--samples, default 50,000, per surface) to the other's
// nearest triangle. --genus gives the reference genus of a cloud without a reference mesh (the
// horse and the rocker arm: their sources' genus, ../shared/data/README.md). --surface-fit-rounds:
// Parameters::surface_fit_rounds (default: the library's), to compare the finishing stage with and
// without its surface fit.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "nmesh/reconstruct.h"
#include "number_list.h"
#include "summary.h"
#include "surface_distance.h"

namespace {

using nmesh::IndexedMesh;
using nmesh::Vec3;

using nmesh::bench::area;
using nmesh::bench::Distances;
using nmesh::bench::distances;
using nmesh::bench::sample_surface;
using nmesh::bench::triangle_area;

// The largest piece's share of the area (pieces: triangles joined through shared vertices).
double largest_piece_share(const IndexedMesh& m) {
    std::vector<std::uint32_t> parent(m.positions.size());
    for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
    const auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (const auto& t : m.triangles) {
        parent[find(t[1])] = find(t[0]);
        parent[find(t[2])] = find(t[0]);
    }
    std::map<std::uint32_t, double> piece;
    double total = 0.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        const double a = triangle_area(m, t);
        piece[find(m.triangles[t][0])] += a;
        total += a;
    }
    double best = 0.0;
    for (const auto& [root, a] : piece) best = std::max(best, a);
    return total > 0.0 ? best / total : 0.0;
}

struct Reference {
    bool present = false;
    bool closed = false;
    int genus = -1;  // -1 unless a manifold (holes allowed)
    double hausdorff_rel = 0.0;  // the reference against the cloud
    double area = 0.0;
    std::vector<Vec3> samples;
    IndexedMesh mesh;
};

struct Run {
    std::string cloud, topology;
    std::uint32_t asked = 0, vertices = 0;
    std::uint64_t seed = 0;
    std::string error;
    int genus = -1, ref_genus = -1;
    bool checked = false;  // topology closed and a manifold reference: the closed goals apply
    std::size_t crossing_pairs = 0, inward_faces = 0, loops = 0, components = 0;
    double hausdorff_rel = 0.0, ref_hausdorff_rel = 0.0;
    double to_ref_mean = 0.0, to_ref_max = 0.0, from_ref_mean = 0.0, from_ref_max = 0.0;  // % diagonal
    double area_ratio = 0.0, piece_share = 0.0;
    double p2s_mean_rel = 0.0, share_under_10 = 0.0;
    double seconds = 0.0, seconds_learning = 0.0, seconds_finish = 0.0;
};

bool failed_closed_goal(const Run& r) {
    return r.checked &&
           (!r.error.empty() || r.crossing_pairs > 0 || r.inward_faces > 0 || (r.ref_genus >= 0 && r.genus != r.ref_genus));
}

// What --check enforces on every run: no error, no crossing pair; in topology closed, no inward
// face and no genus above the reference's (a handle missed is a goal failure, counted apart).
bool fails_check(const Run& r) {
    if (!r.error.empty() || r.crossing_pairs > 0) return true;
    return r.checked && (r.inward_faces > 0 || (r.ref_genus >= 0 && r.genus > r.ref_genus));
}

std::string name_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

std::string fmt(const char* f, double x) {
    char b[64];
    std::snprintf(b, sizeof b, f, x);
    return b;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> clouds;
    std::vector<std::uint64_t> seeds, fractions, sizes;
    std::string csv, md;
    bool check = false;
    nmesh::Topology topology = nmesh::Topology::closed;
    std::size_t samples = 50000;
    std::map<std::string, int> known_genus;  // --genus
    std::uint32_t surface_fit_rounds = nmesh::Parameters{}.surface_fit_rounds;
    try {
        const nmesh::cli::Arguments args(argc, argv, 1, {"--check"},
                                         {"--csv", "--md", "--seeds", "--fractions", "--sizes", "--topology",
                                          "--samples", "--genus", "--surface-fit-rounds"});
        clouds = args.positional();
        seeds = nmesh::bench::parse_range(args.text("--seeds", "1-10"));
        fractions = nmesh::bench::parse_range(args.text("--fractions", "2,6"));
        if (args.has("--sizes")) sizes = nmesh::bench::parse_range(args.text("--sizes"));
        if (args.has("--topology")) topology = nmesh::parse_topology(args.text("--topology").c_str());
        samples = std::stoull(args.text("--samples", "50000"));
        surface_fit_rounds = std::uint32_t(args.count("--surface-fit-rounds", surface_fit_rounds));
        std::stringstream genus_list(args.text("--genus"));
        for (std::string item; std::getline(genus_list, item, ',');) {
            const auto eq = item.find('=');
            if (eq == std::string::npos) throw nmesh::cli::UsageError("--genus takes NAME=G,...");
            known_genus[item.substr(0, eq)] = std::stoi(item.substr(eq + 1));
        }
        csv = args.text("--csv");
        md = args.text("--md");
        check = args.has("--check");
        if (clouds.empty() || csv.empty() || md.empty()) throw nmesh::cli::UsageError("give clouds, --csv and --md");
    } catch (const std::exception& e) {
        std::fprintf(stderr,
                     "%s\nusage: %s CLOUD... --csv OUT.csv --md OUT.md [--seeds 1-10] [--fractions 2,6] "
                     "[--sizes N,...] [--topology closed|open|sphere] [--check] [--samples N] [--genus NAME=G,...] "
                     "[--surface-fit-rounds N]\n",
                     e.what(), argv[0]);
        return 2;
    }

    std::vector<Run> runs;
    const auto start = std::chrono::steady_clock::now();
    try {
        for (const std::string& path : clouds) {
            const nmesh::PointCloud cloud = nmesh::read_points(path);
            const std::string name = name_of(path);
            Reference ref;
            const std::filesystem::path ref_path =
                std::filesystem::path(path).parent_path() / (name + "_mesh.ply");
            if (std::filesystem::exists(ref_path)) {
                ref.present = true;
                ref.mesh = nmesh::read_mesh(ref_path.string());
                const nmesh::MeshTopology topo = nmesh::mesh_topology(ref.mesh);
                ref.closed = topo.closed && topo.manifold;
                ref.genus = topo.manifold ? topo.genus : -1;
                nmesh::EvalOptions o;
                o.surface_samples = samples;
                ref.hausdorff_rel = nmesh::evaluate(cloud.points, ref.mesh, o).hausdorff_rel;
                ref.area = area(ref.mesh);
                ref.samples = sample_surface(ref.mesh, samples, 7);
            }
            if (!ref.present && known_genus.count(name)) ref.genus = known_genus[name];
            const double diagonal = double(nmesh::norm(nmesh::bounding_box(cloud.points).max - nmesh::bounding_box(cloud.points).min));
            const nmesh::Topology mode = topology;
            std::vector<std::uint32_t> counts;
            for (const std::uint64_t s : sizes) counts.push_back(std::uint32_t(s));
            if (sizes.empty())
                for (const std::uint64_t f : fractions) counts.push_back(std::uint32_t(cloud.size() / f));
            for (const std::uint32_t n : counts) {
                for (const std::uint64_t seed : seeds) {
                    Run r;
                    r.cloud = name;
                    r.topology = nmesh::topology_name(mode);
                    r.asked = n;
                    r.seed = seed;
                    r.ref_genus = ref.genus;
                    r.checked = mode == nmesh::Topology::closed && ref.genus >= 0;
                    r.ref_hausdorff_rel = ref.hausdorff_rel;
                    nmesh::Parameters p;
                    p.target_vertices = n;
                    p.seed = seed;
                    p.topology = mode;
                    p.surface_fit_rounds = surface_fit_rounds;
                    try {
                        const auto t0 = std::chrono::steady_clock::now();
                        const nmesh::Result res = nmesh::reconstruct(cloud, p);
                        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                        r.seconds_learning = res.stats.seconds;
                        r.seconds_finish = res.stats.seconds_finish;
                        nmesh::EvalOptions o;
                        o.surface_samples = samples;
                        const nmesh::QualityReport q = nmesh::evaluate(cloud.points, res.mesh, o);
                        r.vertices = std::uint32_t(q.vertices - q.isolated_vertices);
                        r.genus = q.genus;
                        r.crossing_pairs = q.self_intersections;
                        r.inward_faces = q.inward_faces;
                        r.loops = q.boundary_loops;
                        r.components = q.components;
                        r.hausdorff_rel = q.hausdorff_rel;
                        r.p2s_mean_rel = q.p2s_mean_rel;
                        r.share_under_10 = q.share_under_10deg;
                        r.piece_share = largest_piece_share(res.mesh);
                        if (ref.present) {
                            const Distances to = distances(sample_surface(res.mesh, samples, 11), ref.mesh);
                            const Distances from = distances(ref.samples, res.mesh);
                            r.to_ref_mean = 100.0 * to.mean / diagonal;
                            r.to_ref_max = 100.0 * to.max / diagonal;
                            r.from_ref_mean = 100.0 * from.mean / diagonal;
                            r.from_ref_max = 100.0 * from.max / diagonal;
                            r.area_ratio = area(res.mesh) / ref.area;
                        }
                    } catch (const nmesh::Error& e) {
                        r.error = e.what();
                    }
                    std::fprintf(stderr,
                                 "%s %u seed %llu %s: genus %d (ref %d), H %.2f%% (ref %.2f%%), %zu pairs, %zu inward, "
                                 "%zu loops, %zu pieces, area %.3f, %.2f s%s%s\n",
                                 name.c_str(), n, (unsigned long long)seed, r.topology.c_str(), r.genus, r.ref_genus,
                                 100.0 * r.hausdorff_rel, 100.0 * r.ref_hausdorff_rel, r.crossing_pairs,
                                 r.inward_faces, r.loops, r.components, r.area_ratio, r.seconds,
                                 r.error.empty() ? "" : ", error: ", r.error.c_str());
                    runs.push_back(r);
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
        out << "cloud,topology,asked,vertices,seed,genus,ref_genus,hausdorff_rel,ref_hausdorff_rel,to_ref_mean,to_ref_max,"
               "from_ref_mean,from_ref_max,crossing_pairs,inward_faces,boundary_loops,components,piece_share,"
               "area_ratio,p2s_mean_rel,share_under_10deg,seconds,seconds_learning,seconds_finish,error\n";
        out.precision(6);
        for (const Run& r : runs)
            out << r.cloud << ',' << r.topology << ',' << r.asked << ',' << r.vertices << ',' << r.seed << ',' << r.genus
                << ',' << r.ref_genus << ',' << r.hausdorff_rel << ',' << r.ref_hausdorff_rel << ',' << r.to_ref_mean
                << ',' << r.to_ref_max << ',' << r.from_ref_mean << ',' << r.from_ref_max << ',' << r.crossing_pairs
                << ',' << r.inward_faces << ',' << r.loops << ',' << r.components << ',' << r.piece_share << ','
                << r.area_ratio << ',' << r.p2s_mean_rel << ',' << r.share_under_10 << ',' << r.seconds << ','
                << r.seconds_learning << ',' << r.seconds_finish << ",\"" << r.error << "\"\n";
    }
    // One row per cloud and size, over the seeds.
    std::vector<std::pair<std::string, std::uint32_t>> keys;
    std::map<std::pair<std::string, std::uint32_t>, std::vector<const Run*>> groups;
    for (const Run& r : runs) {
        const auto key = std::make_pair(r.cloud, r.asked);
        if (groups[key].empty()) keys.push_back(key);
        groups[key].push_back(&r);
    }
    std::ofstream out(md);
    out << "| cloud | mode | vertices asked | runs | genus (ref) | genus (runs) | H / ref's own (median, max) | "
           "to ref (mean, max %) | from ref (mean, max %) | with crossings | with inward | loops (min-max) | "
           "pieces (max) | largest piece share (min) | area / ref (min-max) | vertices (min) | seconds (median) | "
           "errors | goal failures |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::size_t failures = 0, closed_runs = 0, check_failures = 0;
    for (const auto& key : keys) {
        const auto& g = groups[key];
        std::map<int, int> genera;
        std::vector<double> h, to_mean, to_max, from_mean, from_max, area_ratio, secs, share;
        std::size_t crossing = 0, inward = 0, errors = 0, fails = 0, min_loops = SIZE_MAX, max_loops = 0, pieces = 0;
        std::uint32_t min_vertices = UINT32_MAX;
        for (const Run* r : g) {
            if (r->checked) ++closed_runs;
            if (failed_closed_goal(*r)) ++fails;
            if (fails_check(*r)) ++check_failures;
            if (!r->error.empty()) {
                ++errors;
                continue;
            }
            ++genera[r->genus];
            if (r->ref_hausdorff_rel > 0.0) h.push_back(r->hausdorff_rel / r->ref_hausdorff_rel);
            to_mean.push_back(r->to_ref_mean);
            to_max.push_back(r->to_ref_max);
            from_mean.push_back(r->from_ref_mean);
            from_max.push_back(r->from_ref_max);
            area_ratio.push_back(r->area_ratio);
            secs.push_back(r->seconds);
            share.push_back(r->piece_share);
            crossing += r->crossing_pairs > 0;
            inward += r->inward_faces > 0;
            min_loops = std::min(min_loops, r->loops);
            max_loops = std::max(max_loops, r->loops);
            pieces = std::max(pieces, r->components);
            min_vertices = std::min(min_vertices, r->vertices);
        }
        failures += fails;
        std::string genus_text;
        for (auto it = genera.rbegin(); it != genera.rend(); ++it)
            genus_text += (genus_text.empty() ? "" : ", ") + std::to_string(it->first) + " (" + std::to_string(it->second) + ")";
        const auto med = [](const std::vector<double>& v) { return v.empty() ? 0.0 : nmesh::bench::summarize(v).median; };
        const auto mx = [](const std::vector<double>& v) { return v.empty() ? 0.0 : nmesh::bench::summarize(v).max; };
        const auto mn = [](const std::vector<double>& v) { return v.empty() ? 0.0 : nmesh::bench::summarize(v).min; };
        const Run& first = *g.front();
        out << "| " << key.first << " | " << first.topology << " | " << key.second << " | " << g.size() << " | "
            << (first.ref_genus >= 0 ? std::to_string(first.ref_genus) : std::string("open")) << " | " << genus_text
            << " | " << fmt("%.2f", med(h)) << ", " << fmt("%.2f", mx(h)) << " | " << fmt("%.3f", med(to_mean)) << ", "
            << fmt("%.2f", mx(to_max)) << " | " << fmt("%.3f", med(from_mean)) << ", " << fmt("%.2f", mx(from_max))
            << " | " << crossing << " | " << inward << " | " << (min_loops == SIZE_MAX ? 0 : min_loops) << "-"
            << max_loops << " | " << pieces << " | " << fmt("%.3f", mn(share)) << " | " << fmt("%.3f", mn(area_ratio))
            << "-" << fmt("%.3f", mx(area_ratio)) << " | " << (min_vertices == UINT32_MAX ? 0 : min_vertices) << " | "
            << fmt("%.2f", med(secs)) << " | " << errors << " | " << fails << " |\n";
    }
    out << "\n" << runs.size() << " runs in " << fmt("%.0f", seconds) << " s; closed-cloud runs failing a goal (error, "
        << "crossing pair, inward face or genus other than the reference's): " << failures << " of " << closed_runs
        << "; runs with an error, a crossing pair, or in topology closed an inward face or a genus above the "
        << "reference's: " << check_failures << " of " << runs.size() << ".\n";
    std::fprintf(stderr, "%zu runs in %.0f s; %zu of %zu closed-cloud runs fail a goal; %zu runs fail the check\n",
                 runs.size(), seconds, failures, closed_runs, check_failures);
    return check && check_failures > 0 ? 1 : 0;
}
