// bench/surface_fit_sweep.cpp — the choice of the surface fit's constants (nmesh/finish/surface_fit.h): each
// cloud is reconstructed once without the fit, then the fit is run on that mesh with each setting,
// round by round, and the mesh measured after every round: the distance to the reference surface
// both ways (their mean, the chamfer distance) and the mean point-to-surface distance from the
// cloud, in % of the diagonal, the share of triangles under 10 degrees, crossing pairs, the
// Hausdorff distance to the cloud and the fit's time. One CSV row per run, setting and number of
// rounds (0: the mesh without the fit; each count a fit of its own from the unfitted mesh).
//
//   surface_fit_sweep CLOUD... --csv OUT.csv [--seeds 1-3] [--fractions 3,10] [--sizes N,...]
//                     [--rounds 1,2,3] [--smoothness 0.03,0.1,0.3] [--reach 1] [--step 0.5] [--samples N]
//                     [--normal-only]
//
// --normal-only: moves along the vertex normals only (SurfaceFitOptions::normal_only).
//
// The fit runs here on the output mesh, outside the stage: the points' normals come from that
// mesh (CloudSurface without the samples' sides), and it sees every point of the cloud (the
// stage sees the points of the cloud's index, all of them below 64 per vertex).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/surface_fit.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/io.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/metrics.h"
#include "nmesh/reconstruct.h"
#include "number_list.h"
#include "surface_distance.h"

namespace {

std::vector<double> parse_numbers(const std::string& text) {
    std::vector<double> out;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');) out.push_back(std::stod(part));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> clouds;
    std::vector<std::uint64_t> seeds, fractions, sizes;
    std::vector<double> smoothness, reach, step;
    std::string csv;
    std::vector<std::uint64_t> rounds;
    std::size_t samples = 50000;
    bool normal_only = false;
    try {
        const nmesh::cli::Arguments args(argc, argv, 1, {"--normal-only"},
                                         {"--csv", "--seeds", "--fractions", "--sizes", "--rounds", "--smoothness",
                                          "--reach", "--step", "--samples"});
        clouds = args.positional();
        seeds = nmesh::bench::parse_range(args.text("--seeds", "1-3"));
        fractions = nmesh::bench::parse_range(args.text("--fractions", "3,10"));
        if (args.has("--sizes")) sizes = nmesh::bench::parse_range(args.text("--sizes"));
        rounds = nmesh::bench::parse_range(args.text("--rounds", "1,2,3"));
        smoothness = parse_numbers(args.text("--smoothness", "0.03,0.1,0.3"));
        reach = parse_numbers(args.text("--reach", "1"));
        step = parse_numbers(args.text("--step", "0.5"));
        samples = std::stoull(args.text("--samples", "50000"));
        normal_only = args.has("--normal-only");
        csv = args.text("--csv");
        if (clouds.empty() || csv.empty()) throw nmesh::cli::UsageError("give clouds and --csv");
    } catch (const std::exception& e) {
        std::fprintf(
            stderr,
            "%s\nusage: %s CLOUD... --csv OUT.csv [--seeds 1-3] [--fractions 3,10] [--sizes N,...] "
            "[--rounds 1,2,3] [--smoothness 0.03,0.1,0.3] [--reach 1] [--step 0.5] [--samples N] [--normal-only]\n",
            e.what(), argv[0]);
        return 2;
    }
    std::ofstream out(csv);
    out << "cloud,vertices,seed,smoothness,reach,step,round,chamfer,to_ref_mean,from_ref_mean,p2s_mean_rel,"
           "share_under_10deg,crossing_pairs,inward_faces,hausdorff_rel,fit_seconds,moves,halved,undone\n";
    out.precision(6);
    try {
        for (const std::string& path : clouds) {
            const nmesh::PointCloud cloud = nmesh::read_points(path);
            const std::string name = std::filesystem::path(path).stem().string();
            const auto ref_path = std::filesystem::path(path).parent_path() / (name + "_mesh.ply");
            const bool has_ref = std::filesystem::exists(ref_path);
            const nmesh::IndexedMesh ref = has_ref ? nmesh::read_mesh(ref_path.string()) : nmesh::IndexedMesh();
            const std::vector<nmesh::Vec3> ref_samples =
                has_ref ? nmesh::bench::sample_surface(ref, samples, 7) : std::vector<nmesh::Vec3>();
            const auto box = nmesh::bounding_box(cloud.points);
            const double diagonal = double(nmesh::norm(box.max - box.min));
            std::vector<std::uint32_t> counts;
            for (const std::uint64_t s : sizes) counts.push_back(std::uint32_t(s));
            if (sizes.empty())
                for (const std::uint64_t f : fractions) counts.push_back(std::uint32_t(cloud.size() / f));
            for (const std::uint32_t n : counts) {
                for (const std::uint64_t seed : seeds) {
                    nmesh::Parameters p;
                    p.target_vertices = n;
                    p.seed = seed;
                    p.surface_fit_rounds = 0;
                    p.exchange_passes = 0;  // the mesh the fit's settings were chosen on
                    const nmesh::Result res = nmesh::reconstruct(cloud, p);
                    const auto measure = [&](const nmesh::IndexedMesh& m, double x, double r, double st, int round,
                                             double seconds, const nmesh::SurfaceFitResult& fit) {
                        nmesh::EvalOptions o;
                        o.surface_samples = samples;
                        const nmesh::QualityReport q = nmesh::evaluate(cloud.points, m, o);
                        double to = 0.0, from = 0.0;
                        if (has_ref) {
                            to = nmesh::bench::distances(nmesh::bench::sample_surface(m, samples, 11), ref).mean;
                            from = nmesh::bench::distances(ref_samples, m).mean;
                        }
                        out << name << ',' << n << ',' << seed << ',' << x << ',' << r << ',' << st << ',' << round
                            << ',' << 50.0 * (to + from) / diagonal << ',' << 100.0 * to / diagonal << ','
                            << 100.0 * from / diagonal << ',' << 100.0 * q.p2s_mean_rel << ',' << q.share_under_10deg
                            << ',' << q.self_intersections << ',' << q.inward_faces << ',' << q.hausdorff_rel << ','
                            << seconds << ',' << fit.moves << ',' << fit.halved << ',' << fit.undone << '\n';
                        out.flush();
                        std::fprintf(stderr,
                                     "%s %u seed %llu k %.3g reach %.3g step %.3g round %d: chamfer %.4f%%, "
                                     "p2s %.4f%%, <10deg %.3f%%, %zu pairs, %.3f s\n",
                                     name.c_str(), n, (unsigned long long)seed, x, r, st, round,
                                     50.0 * (to + from) / diagonal, 100.0 * q.p2s_mean_rel, 100.0 * q.share_under_10deg,
                                     q.self_intersections, seconds);
                    };
                    const std::size_t pairs_before = nmesh::count_self_intersections(res.mesh);
                    measure(res.mesh, 0, 0, 0, 0, 0.0, {});
                    for (const double x : smoothness)
                        for (const double r : reach)
                            for (const double st : step) {
                                for (const std::uint64_t count : rounds) {
                                    nmesh::Mesh mesh = nmesh::Mesh::from_indexed(res.mesh, true);
                                    mesh.build_faces();
                                    const nmesh::CloudSurface surface(cloud.points, mesh);
                                    nmesh::SurfaceFitOptions o;
                                    o.rounds = int(count);
                                    o.smoothness = float(x);
                                    o.reach = float(r);
                                    o.step_limit = float(st);
                                    o.normal_only = normal_only;
                                    o.known_clean = pairs_before == 0;  // as the stage knows it after its repair
                                    const auto t0 = std::chrono::steady_clock::now();
                                    const nmesh::SurfaceFitResult fit = nmesh::fit_surface(mesh, surface, o);
                                    const double seconds =
                                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                                    measure(mesh.to_indexed(), x, r, st, int(count), seconds, fit);
                                }
                            }
                }
            }
        }
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
