// Renders the pictures of the README under docs/:
//   - growth.png: the bunny mesh as it grows (100, 1,000, 10,000 and 30,000 vertices), one run;
//   - figures 6-9 of the paper: basic Neural Meshes and Neural Meshes ES at the worst
//     (alpha_w 0.01, alpha_n 0.002) and best (0.08, 0.01) settings, 5,000 vertices;
//   - figure 10: the 30,000-vertex bunny, and its error map (distance to the scan);
//   - table1_heatmap.png: the median DM(X,T) of bench/results/paper/table1.csv for both
//     algorithms side by side (rows alpha_n, columns alpha_w; one colour scale for both).
//
//     paper_figures CLOUD.ply TABLE1.csv OUTDIR
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/metrics.h"
#include "nmesh/render/png_writer.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/io.h"
#include "nmesh/reconstruct.h"
#include "nmesh/render.h"

namespace {

constexpr int kTile = 400;  // pixels per rendered tile: small files, still readable

nmesh::Image tile(const nmesh::IndexedMesh& mesh, const std::vector<float>* values = nullptr) {
    nmesh::RenderOptions o;
    o.width = o.height = kTile;
    o.view = nmesh::View::front();
    o.wireframe = mesh.positions.size() <= 10000;
    o.vertex_values = values;
    return nmesh::render(mesh, o);
}

// Images side by side, in one row.
void write_row(const std::string& path, const std::vector<nmesh::Image>& images) {
    int width = 0, height = 0;
    for (const nmesh::Image& im : images) {
        width += im.width;
        height = std::max(height, im.height);
    }
    std::vector<std::uint8_t> rgb(std::size_t(width) * height * 3, 255);
    int x0 = 0;
    for (const nmesh::Image& im : images) {
        for (int y = 0; y < im.height; ++y)
            std::copy_n(&im.rgb[std::size_t(y) * im.width * 3], std::size_t(im.width) * 3,
                        &rgb[(std::size_t(y) * width + x0) * 3]);
        x0 += im.width;
    }
    nmesh::write_png(path, width, height, rgb);
    std::printf("wrote %s (%dx%d)\n", path.c_str(), width, height);
}

nmesh::IndexedMesh run(const nmesh::PointCloud& cloud, std::uint32_t n, double aw, double an, bool swap) {
    nmesh::Parameters p;
    p.target_vertices = n;
    p.alpha_w = aw;
    p.alpha_n = an;
    p.edge_swap = swap;
    p.finish = false;  // figures 6-9 compare the paper's algorithms as published
    p.fold_guard = false;
    p.topology = nmesh::Topology::sphere;
    return nmesh::reconstruct(cloud, p).mesh;
}

// The Table 1 heat map: one block per (alpha_n, alpha_w) cell, NM on the left, NM ES on the
// right, both on one blue (low DM, good) to red (high) scale.
void write_heatmap(const std::string& csv, const std::string& path) {
    std::ifstream in(csv);
    if (!in) throw nmesh::IoError(csv, "cannot open (run bench/run_paper_experiments.sh first)");
    std::string line;
    std::getline(in, line);  // header
    std::map<std::pair<double, double>, double> cells[2];
    std::vector<double> aws, ans;
    double lo = 1e30, hi = 0;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string algo, f;
        std::vector<std::string> fields;
        while (std::getline(ss, f, ',')) fields.push_back(f);
        if (fields.size() < 5) continue;
        const double aw = std::stod(fields[1]), an = std::stod(fields[2]), dm = std::stod(fields[4]);
        cells[fields[0] == "NM_ES"][{an, aw}] = dm;
        aws.push_back(aw);
        ans.push_back(an);
        lo = std::min(lo, dm);
        hi = std::max(hi, dm);
    }
    std::sort(aws.begin(), aws.end());
    aws.erase(std::unique(aws.begin(), aws.end()), aws.end());
    std::sort(ans.begin(), ans.end());
    ans.erase(std::unique(ans.begin(), ans.end()), ans.end());
    constexpr int kCell = 40, kGap = 40;
    const int w = int(aws.size()) * kCell, h = int(ans.size()) * kCell;
    const int width = 2 * w + kGap;
    std::vector<std::uint8_t> rgb(std::size_t(width) * h * 3, 255);
    for (int a = 0; a < 2; ++a)
        for (std::size_t r = 0; r < ans.size(); ++r)
            for (std::size_t c = 0; c < aws.size(); ++c) {
                const auto it = cells[a].find({ans[r], aws[c]});
                if (it == cells[a].end()) continue;
                const auto color = nmesh::ramp_color(float((it->second - lo) / std::max(hi - lo, 1e-30)));
                for (int y = 1; y < kCell - 1; ++y)
                    for (int x = 1; x < kCell - 1; ++x) {
                        const std::size_t px = (std::size_t(r) * kCell + y) * width + a * (w + kGap) + c * kCell + x;
                        for (int k = 0; k < 3; ++k) rgb[px * 3 + k] = color[std::size_t(k)];
                    }
            }
    nmesh::write_png(path, width, h, rgb);
    std::printf("wrote %s: DM from %.6f (blue) to %.6f (red)\n", path.c_str(), lo, hi);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s CLOUD TABLE1.csv OUTDIR\n", argv[0]);
        return 2;
    }
    try {
        const nmesh::PointCloud cloud = nmesh::read_points(argv[1]);
        const std::string out = argv[3];

        // The mesh growing: snapshots of one run.
        std::vector<nmesh::Image> growth;
        nmesh::Parameters p;
        p.target_vertices = 30000;
        nmesh::Callbacks cb;
        cb.snapshot_vertices = {100, 1000, 10000};
        cb.on_snapshot = [&](std::uint32_t, const nmesh::IndexedMesh& m) { growth.push_back(tile(m)); };
        const nmesh::IndexedMesh full = nmesh::reconstruct(cloud, p, cb).mesh;
        growth.push_back(tile(full));
        write_row(out + "/growth.png", growth);

        // Figures 6-9.
        write_row(out + "/worst_nm_vs_es.png",
                  {tile(run(cloud, 5000, 0.01, 0.002, false)), tile(run(cloud, 5000, 0.01, 0.002, true))});
        write_row(out + "/best_nm_vs_es.png",
                  {tile(run(cloud, 5000, 0.08, 0.01, false)), tile(run(cloud, 5000, 0.08, 0.01, true))});

        // Figure 10 and its error map.
        const std::vector<float> error = nmesh::vertex_distances_to_cloud(cloud.points, full);
        nmesh::Parameters learnt_only = p;
        learnt_only.finish = false;
        const nmesh::IndexedMesh learnt = nmesh::reconstruct(cloud, learnt_only).mesh;
        write_row(out + "/bunny_30000.png", {tile(learnt), tile(full), tile(full, &error)});

        write_heatmap(argv[2], out + "/table1_heatmap.png");
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
