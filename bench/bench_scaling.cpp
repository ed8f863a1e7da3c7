// Scaling benchmarks (time and memory against the output size and the input size, and the
// speed of the point readers). One configuration per process, so that peak memory is the
// process's own; bench/run_scaling.sh runs them all and writes the summary.
//
//     bench_scaling output  --vertices N --points P [--runs R] [--cloud FILE] [--csv FILE]
//     bench_scaling input   --vertices N --points P [--runs R] [--cloud FILE] [--csv FILE]
//     (--profile: one more run timing each phase, printed only)
//     bench_scaling loading --points P [--runs R] [--cloud FILE] [--csv FILE]
//
// `output` and `input` measure the same thing (a reconstruction of N vertices from a cloud of
// about P points); the mode only labels the CSV row. `loading` writes the cloud to a binary PLY
// and an XYZ text file in a scratch directory ($TMPDIR or /tmp, removed afterwards), reads each
// once to warm the page cache, then times read_points R times per file.
//
// The clouds. The base cloud is FILE (default: the bundled bunny, 35,947 points). A cloud of
// P points is the base cloud upsampled k = round(P / base) times (k = 1: the base cloud itself):
// every base point p is kept, followed by k - 1 new points, each drawn uniformly from the
// triangle (p, (p + a) / 2, (p + b) / 2), where a and b are two distinct points drawn among the
// 6 nearest neighbours of p in the base cloud. A new point is thus at most half a neighbour
// distance h from p (about half the scan spacing), in the plane of p, a and b: off the scanned
// surface by at most about h^2 / (8 R) where the curvature radius is R (2% of h for R = 6 h).
// This resamples the surface more densely; it is not a cluster of copies of p. Copies with a
// jitter well under the scan spacing would add points but hardly any new places where vertices
// can win signals, and the mesh only grows to about 1.3 times the number of such places
// (README.md, target size and cloud size): 1,000,000 vertices need the denser sampling.
// Deterministic: a fixed seed and nmesh::Random (the same stream on every platform); the
// neighbours are exact, ties to the smaller index.
//
// Times. `seconds` is Statistics::seconds of nmesh::reconstruct (learning, including the
// normalisation of the cloud and the building of its nearest-point index; excluding the reading
// or generation of the cloud). `setup` is the same figure for a 4-vertex target (4 Cvs iterations of the tetrahedron,
// normalisation, an index of as many points as the timed runs': setup_only()), measured
// separately (median of R runs); `loop` is
// seconds - setup. Each figure is the median, minimum and maximum of R runs with the default
// parameters (Table 2 of the paper, seed 1: all runs are identical but for their timing), except
// that the finishing stage after learning (Parameters::finish) is switched off: these are the
// figures of the learning algorithm.
//
// Memory, read from /proc/self/status (Linux); peaks are VmHWM, reset through
// /proc/self/clear_refs. The cloud (PointCloud: 12 bytes per point) is in memory throughout and is
// never counted. Two measurements, each from the same fresh state (the cloud just generated):
//   - the input storage, in a forked child: reconstruct() with setup_only()'s 4-vertex target,
//     VmRSS and VmHWM read from the progress report that reconstruct() makes when the learning
//     ends, while the engine is still alive, minus VmRSS before the call. The resident memory the
//     engine adds per input point (the nearest-point index, which holds a sorted copy of the
//     normalised points, or of the stratified sample of them that stands for a cloud of more than
//     Parameters::index_points_per_vertex points per vertex; the engine normalises its samples
//     on the fly and keeps no copy of its own), and the peak per input point while the engine is
//     built (the index's temporary arrays included). The index alone per
//     Statistics::index_bytes (PointGrid::memory_bytes) of the timed runs is given too;
//   - the mesh, in the first timed run: VmHWM from the first progress report (65,536
//     iterations, after the engine is built) to the return of reconstruct(), minus VmRSS before
//     the call, minus the input storage. Bytes per vertex = that / N. reconstruct() builds the
//     output mesh (reported on its own as output bytes per vertex) after it has freed the
//     engine, so the peak is that of the learning unless the mesh and its output copy weigh more.
// (peak - before) / N is the whole call's peak over VmRSS before it, input storage included.
#include <algorithm>
#include <cstdarg>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/spatial/cloud_sample.h"
#include "nmesh/io.h"
#include "nmesh/util/random.h"
#include "nmesh/reconstruct.h"
#include "summary.h"

namespace {

using Clock = std::chrono::steady_clock;

using nmesh::bench::summarize;
using nmesh::bench::Summary;

// ---- memory (Linux /proc) ----------------------------------------------------------------------

struct MemoryStatus {
    std::int64_t rss = -1, hwm = -1;  // bytes; -1 when unknown
};

MemoryStatus memory_status() {
    MemoryStatus m;
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        long long kb = 0;
        if (std::sscanf(line.c_str(), "VmRSS: %lld kB", &kb) == 1) m.rss = kb * 1024;
        if (std::sscanf(line.c_str(), "VmHWM: %lld kB", &kb) == 1) m.hwm = kb * 1024;
    }
    return m;
}

// Resets VmHWM to the current VmRSS; false when the kernel does not allow it.
bool reset_peak() {
    std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
    if (!f) return false;
    const bool ok = std::fputs("5", f) >= 0;
    return std::fclose(f) == 0 && ok;
}

// ---- clouds ------------------------------------------------------------------------------------

constexpr int kNeighbours = 6;
constexpr std::uint64_t kUpsampleSeed = 7;

// The kNeighbours nearest neighbours of every point (itself excluded), exact, ties to the smaller
// index, through a uniform grid of about 2 points per cell on a surface.
std::vector<std::uint32_t> nearest_neighbours(const std::vector<nmesh::Vec3>& pts) {
    const std::size_t n = pts.size();
    const nmesh::BoundingBox box = nmesh::bounding_box(pts);
    const double e[3] = {double(box.max.x) - box.min.x, double(box.max.y) - box.min.y, double(box.max.z) - box.min.z};
    const double half_area = e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    double cell = half_area > 0 ? std::sqrt(2.0 * half_area / double(n)) : std::max({e[0], e[1], e[2], 1e-30});
    std::int64_t dims[3];
    auto fit = [&] {
        double total = 1;
        for (int a = 0; a < 3; ++a) {
            dims[a] = std::max<std::int64_t>(1, std::int64_t(std::ceil(e[a] / cell)));
            total *= double(dims[a]);
        }
        return total;
    };
    while (fit() > 4.0 * double(n) + 64) cell *= 1.25;
    const double lo[3] = {box.min.x, box.min.y, box.min.z};
    auto coord = [&](const nmesh::Vec3& p, int a) {
        return std::clamp<std::int64_t>(std::int64_t((double(p[a]) - lo[a]) / cell), 0, dims[a] - 1);
    };
    auto cell_of = [&](std::int64_t i, std::int64_t j, std::int64_t k) { return (k * dims[1] + j) * dims[0] + i; };
    const std::size_t cells = std::size_t(dims[0] * dims[1] * dims[2]);
    std::vector<std::uint32_t> start(cells + 1, 0), order(n);
    for (const nmesh::Vec3& p : pts) ++start[std::size_t(cell_of(coord(p, 0), coord(p, 1), coord(p, 2))) + 1];
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
        const nmesh::Vec3& p = pts[i];
        order[fill[std::size_t(cell_of(coord(p, 0), coord(p, 1), coord(p, 2)))]++] = std::uint32_t(i);
    }
    std::vector<std::uint32_t> result(n * kNeighbours);
    std::vector<std::pair<double, std::uint32_t>> best;
    for (std::size_t i = 0; i < n; ++i) {
        const nmesh::Vec3& p = pts[i];
        const std::int64_t c[3] = {coord(p, 0), coord(p, 1), coord(p, 2)};
        best.clear();
        auto consider = [&](std::int64_t ci, std::int64_t cj, std::int64_t ck) {
            const std::size_t id = std::size_t(cell_of(ci, cj, ck));
            for (std::uint32_t s = start[id]; s < start[id + 1]; ++s) {
                const std::uint32_t q = order[s];
                if (q == i) continue;
                const double dx = double(pts[q].x) - p.x, dy = double(pts[q].y) - p.y, dz = double(pts[q].z) - p.z;
                best.emplace_back(dx * dx + dy * dy + dz * dz, q);
            }
        };
        // Shell r: the cells at Chebyshev distance exactly r from p's cell. After shell r, every
        // unscanned point is at least r cells away from p.
        const std::int64_t max_r = std::max({dims[0], dims[1], dims[2]});
        for (std::int64_t r = 0; r <= max_r; ++r) {
            for (std::int64_t k = c[2] - r; k <= c[2] + r; ++k)
                for (std::int64_t j = c[1] - r; j <= c[1] + r; ++j)
                    for (std::int64_t ii = c[0] - r; ii <= c[0] + r; ++ii) {
                        if (std::max({std::abs(ii - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
                        if (ii < 0 || j < 0 || k < 0 || ii >= dims[0] || j >= dims[1] || k >= dims[2]) continue;
                        consider(ii, j, k);
                    }
            if (best.size() >= std::size_t(kNeighbours)) {
                std::partial_sort(best.begin(), best.begin() + kNeighbours, best.end());
                const double reach = double(r) * cell;
                if (best[kNeighbours - 1].first <= reach * reach) break;
            }
        }
        if (best.size() < std::size_t(kNeighbours)) throw nmesh::InputError("the base cloud needs at least 7 points");
        std::partial_sort(best.begin(), best.begin() + kNeighbours, best.end());
        for (int t = 0; t < kNeighbours; ++t) result[i * kNeighbours + std::size_t(t)] = best[std::size_t(t)].second;
    }
    return result;
}

// The base cloud upsampled k times (see the comment at the top of the file).
nmesh::PointCloud upsample(const nmesh::PointCloud& base, std::uint32_t k) {
    if (k <= 1) return base;
    const std::vector<std::uint32_t> nb = nearest_neighbours(base.points);
    nmesh::PointCloud out;
    out.points.reserve(base.size() * k);
    nmesh::Random rng(kUpsampleSeed);
    for (std::size_t i = 0; i < base.size(); ++i) {
        const nmesh::Vec3 p = base.points[i];
        out.points.push_back(p);
        for (std::uint32_t j = 1; j < k; ++j) {
            const std::uint32_t ia = rng.below(kNeighbours);
            std::uint32_t ib = rng.below(kNeighbours - 1);
            if (ib >= ia) ++ib;
            const nmesh::Vec3 a = base.points[nb[i * kNeighbours + ia]];
            const nmesh::Vec3 b = base.points[nb[i * kNeighbours + ib]];
            double u = rng.uniform(), v = rng.uniform();
            if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
            u *= 0.5;
            v *= 0.5;
            out.points.emplace_back(float(p.x + u * (double(a.x) - p.x) + v * (double(b.x) - p.x)),
                                    float(p.y + u * (double(a.y) - p.y) + v * (double(b.y) - p.y)),
                                    float(p.z + u * (double(a.z) - p.z) + v * (double(b.z) - p.z)));
        }
    }
    return out;
}

// ---- modes -------------------------------------------------------------------------------------

struct Options {
    std::string mode;                               // output, input, loading or pair
    std::uint32_t vertices = 30000;                 // target size (output and input)
    std::uint64_t points = 0;                       // cloud size wanted: the base upsampled ~points/base times
    int runs = 5;                                   // timed runs per figure
    std::string cloud = "examples/data/bunny.ply";  // the base cloud
    std::string csv;                                // a CSV line is appended here when set
    bool profile = false;                           // one more run timing each phase (printed only)
};

// printf into a std::string.
std::string format(const char* fmt, ...) {
    va_list args;
    va_start(args, fmt);
    va_list again;
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, fmt, args);
    va_end(args);
    std::string out(n > 0 ? std::size_t(n) : 0, '\0');
    if (n > 0) std::vsnprintf(out.data(), out.size() + 1, fmt, again);
    va_end(again);
    return out;
}

// Appends `line` to the CSV file `path` (nothing when path is empty; the header is the script's).
void append_csv(const std::string& path, const std::string& line) {
    if (path.empty()) return;
    std::FILE* f = std::fopen(path.c_str(), "a");
    if (!f) throw nmesh::IoError(path, "cannot open for appending");
    const bool ok = std::fputs(line.c_str(), f) >= 0;
    if (std::fclose(f) != 0 || !ok) throw nmesh::IoError(path, "cannot write");
}

// The input storage (see the top of the file), measured in a forked child so that the parent's
// heap is not disturbed: {resident bytes the engine adds, peak bytes while it is built}, both
// over VmRSS before the call, read at the progress report reconstruct() makes when the learning
// ends (the engine still alive) with a 4-vertex target (the tetrahedron only: 4 Cvs iterations).
std::pair<double, double> input_memory(const nmesh::PointCloud& cloud, const nmesh::Parameters& setup_params) {
    int fds[2];
    if (pipe(fds) != 0) throw nmesh::Error("input_memory: cannot create a pipe");
    const pid_t child = fork();
    if (child < 0) throw nmesh::Error("input_memory: cannot fork");
    if (child == 0) {
        close(fds[0]);
        double result[2] = {NAN, NAN};
        if (reset_peak()) {
            const MemoryStatus before = memory_status();
            MemoryStatus at_end;
            const nmesh::Parameters& p = setup_params;
            nmesh::Callbacks cb;
            cb.progress = [&](const nmesh::Progress&) {
                at_end = memory_status();
                return true;
            };
            nmesh::reconstruct(cloud, p, cb);
            if (before.rss >= 0 && at_end.rss >= 0 && at_end.hwm >= 0) {
                result[0] = double(at_end.rss - before.rss);
                result[1] = double(at_end.hwm - before.rss);
            }
        }
        const bool ok = write(fds[1], result, sizeof result) == ssize_t(sizeof result);
        close(fds[1]);
        _exit(ok ? 0 : 1);
    }
    close(fds[1]);
    double result[2] = {NAN, NAN};
    const bool got = read(fds[0], result, sizeof result) == ssize_t(sizeof result);
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    if (!got || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw nmesh::Error("input_memory: the measuring child failed");
    return {result[0], result[1]};
}

// The setup of a run with `params` on a cloud of n points, alone: a 4-vertex target (the
// tetrahedron: 4 Cvs iterations, about 0.1 ms) whose nearest-point index holds as many points as
// that run's (Parameters::index_points_per_vertex scaled up; the stratified sample of a count
// rounded up to a multiple of 4, at most 3 points more).
nmesh::Parameters setup_only(const nmesh::Parameters& params, std::size_t n) {
    nmesh::Parameters p4 = params;
    p4.target_vertices = 4;
    const std::size_t indexed = nmesh::index_point_count(n, params);
    p4.index_points_per_vertex = indexed == n ? 0 : std::uint32_t((indexed + 3) / 4);
    return p4;
}

// `output` and `input`: R timed reconstructions, the setup alone, and the memory.
void run_reconstruction(const Options& o, const nmesh::PointCloud& cloud, std::uint32_t k) {
    nmesh::Parameters params;
    params.target_vertices = o.vertices;
    params.finish = false;  // the figures of the learning algorithm, not of the stage after it
    const double P = double(cloud.size()), N = double(o.vertices);
    const nmesh::Parameters p4 = setup_only(params, cloud.size());
    const auto [input_bytes, setup_peak_bytes] = input_memory(cloud, p4);

    // What the progress callback records in the first run, at the first progress report.
    struct Probe {
        bool active = false, seen = false;
        std::int64_t setup_hwm = -1;
        double next_note = 30.0;
    } probe;
    nmesh::Callbacks callbacks;
    callbacks.progress = [&probe](const nmesh::Progress& p) {
        if (probe.active && !probe.seen && p.iterations > 0) {
            probe.setup_hwm = memory_status().hwm;
            reset_peak();
        }
        probe.seen = true;
        // A line on stderr every 30 s, so that long runs show they advance.
        if (p.seconds >= probe.next_note) {
            std::fprintf(stderr, "  %u / %u vertices, %llu iterations, %.0f s\n", p.vertices, p.target_vertices,
                         (unsigned long long)p.iterations, p.seconds);
            probe.next_note = p.seconds + 30.0;
        }
        return true;
    };

    std::vector<double> seconds, rates, calls;
    std::uint64_t iterations = 0;
    MemoryStatus before, after;
    bool resettable = false;
    std::size_t output_bytes = 0, output_vertices = 0;
    double index_pp = NAN;  // the engine's nearest-point index on its own, per input point
    for (int r = 0; r < o.runs; ++r) {
        probe.active = r == 0;
        probe.seen = false;
        probe.next_note = 30.0;
        if (r == 0) {
            resettable = reset_peak();
            before = memory_status();
        }
        const auto t0 = Clock::now();
        const nmesh::Result res = nmesh::reconstruct(cloud, params, callbacks);
        const double call = std::chrono::duration<double>(Clock::now() - t0).count();
        if (r == 0) {
            after = memory_status();
            output_bytes = res.mesh.positions.capacity() * sizeof(nmesh::Vec3) +
                           res.mesh.triangles.capacity() * sizeof(res.mesh.triangles[0]);
            output_vertices = res.mesh.positions.size();
            index_pp = double(res.stats.index_bytes) / P;
        }
        seconds.push_back(res.stats.seconds);
        rates.push_back(double(res.stats.iterations) / res.stats.seconds);
        calls.push_back(call);
        iterations = res.stats.iterations;
    }
    if (output_vertices != o.vertices)
        throw nmesh::Error("the mesh has " + std::to_string(output_vertices) + " vertices, not " +
                           std::to_string(o.vertices));

    // The setup alone.
    std::vector<double> setup;
    for (int r = 0; r < o.runs; ++r) setup.push_back(nmesh::reconstruct(cloud, p4).stats.seconds);

    const Summary t = summarize(seconds), it = summarize(rates), su = summarize(setup), ca = summarize(calls);
    double mesh_peak = NAN, per_vertex = NAN, raw_pv = NAN;
    if (resettable && probe.setup_hwm >= 0 && before.rss >= 0 && after.hwm >= 0) {
        mesh_peak = double(after.hwm - before.rss) - input_bytes;
        per_vertex = mesh_peak / N;
        raw_pv = double(std::max(probe.setup_hwm, after.hwm) - before.rss) / N;
    }
    const double input_pp = input_bytes / P, setup_peak_pp = setup_peak_bytes / P;
    const double out_pv = double(output_bytes) / N;

    std::printf("%s: %zu points (base x %u) -> %u vertices, %d runs, %llu iterations%s\n", o.mode.c_str(), cloud.size(),
                k, o.vertices, o.runs, (unsigned long long)iterations, " (finishing stage off: learning only)");
    std::printf("  time     median %.3f s  min %.3f  max %.3f  (setup %.3f s, loop %.3f s, whole call %.3f s)\n",
                t.median, t.min, t.max, su.median, t.median - su.median, ca.median);
    std::printf("  rate     median %.3f M it/s  min %.3f  max %.3f\n", it.median / 1e6, it.min / 1e6, it.max / 1e6);
    std::printf(
        "  input    cloud in memory %.1f MB; the engine adds %.1f B/point (index alone %.1f), setup peak "
        "%.1f B/point\n",
        double(before.rss) / 1e6, input_pp, index_pp, setup_peak_pp);
    std::printf("  mesh     peak %.1f MB: %.1f B/vertex (output mesh %.1f); (peak - before) / N %.1f B/vertex\n",
                mesh_peak / 1e6, per_vertex, out_pv, raw_pv);
    if (o.profile) {
        nmesh::Callbacks profiled;
        profiled.profile = true;
        const nmesh::Statistics q = nmesh::reconstruct(cloud, params, profiled).stats;
        const double total =
            q.seconds_winner + q.seconds_update + q.seconds_split + q.seconds_collapse + q.seconds_swap;
        auto share = [&](double x) { return total > 0 ? 100.0 * x / total : 0.0; };
        std::printf(
            "  phases   winner search %.1f%%  move+smooth+counters %.1f%%  split %.1f%%  collapse %.1f%%  swap "
            "%.1f%%  (profiled run: %.3f s; splits %llu, collapses %llu)\n",
            share(q.seconds_winner), share(q.seconds_update), share(q.seconds_split), share(q.seconds_collapse),
            share(q.seconds_swap), q.seconds, (unsigned long long)q.splits, (unsigned long long)q.collapses);
    }
    append_csv(o.csv, format("%s,%zu,%u,%u,%d,%llu,%.4f,%.4f,%.4f,%.0f,%.0f,%.0f,%.4f,%.4f,%.4f,%.1f,%.2f,%.2f,%.2f,"
                             "%.2f,%.1f,%.1f,%.1f\n",
                             o.mode.c_str(), cloud.size(), k, o.vertices, o.runs, (unsigned long long)iterations,
                             t.median, t.min, t.max, it.median, it.min, it.max, su.median, t.median - su.median,
                             ca.median, double(before.rss) / 1e6, setup_peak_pp, input_pp, index_pp, mesh_peak / 1e6,
                             per_vertex, out_pv, raw_pv));
}

// Removes the scratch files and directory however the function leaves.
struct ScratchDir {
    std::string dir;
    std::vector<std::string> files;
    ScratchDir() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/nmesh_loading_XXXXXX";
        std::vector<char> buf(pattern.begin(), pattern.end());
        buf.push_back('\0');
        if (!mkdtemp(buf.data())) throw nmesh::IoError(pattern, "cannot create a scratch directory");
        dir = buf.data();
    }
    std::string file(const std::string& name) {
        files.push_back(dir + "/" + name);
        return files.back();
    }
    ~ScratchDir() {
        for (const std::string& f : files) std::remove(f.c_str());
        rmdir(dir.c_str());
    }
};

void write_file(const std::string& path, const std::string& head, const char* data, std::size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw nmesh::IoError(path, "cannot create");
    const bool ok = std::fwrite(head.data(), 1, head.size(), f) == head.size() && std::fwrite(data, 1, size, f) == size;
    if (std::fclose(f) != 0 || !ok) throw nmesh::IoError(path, "cannot write");
}

// `loading`: the cloud as binary PLY and as XYZ text, each read once, then timed R times.
void run_loading(const Options& o, const nmesh::PointCloud& cloud) {
    ScratchDir scratch;
    const std::uint32_t probe = 1;
    if (*reinterpret_cast<const char*>(&probe) != 1)
        throw nmesh::Error("the PLY writer here assumes a little-endian machine");
    const std::string ply = scratch.file("cloud.ply"), xyz = scratch.file("cloud.xyz");
    write_file(ply,
               "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.size()) +
                   "\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
               reinterpret_cast<const char*>(cloud.points.data()), cloud.size() * sizeof(nmesh::Vec3));
    // XYZ: "x y z" per line, each the shortest decimal text that reads back as the same float.
    std::string text;
    text.reserve(cloud.size() * 36);
    char buf[64];
    for (const nmesh::Vec3& p : cloud.points) {
        for (int a = 0; a < 3; ++a) {
            const auto res = std::to_chars(buf, buf + sizeof buf, p[a]);
            text.append(buf, res.ptr);
            text.push_back(a < 2 ? ' ' : '\n');
        }
    }
    write_file(xyz, "", text.data(), text.size());
    text = std::string();

    for (const std::string& path : {ply, xyz}) {
        nmesh::PointReadReport report;
        const nmesh::PointCloud warm = nmesh::read_points(path, &report);  // warms the page cache
        if (warm.points != cloud.points) throw nmesh::Error(path + ": the points read back differ from those written");
        std::vector<double> seconds;
        for (int r = 0; r < o.runs; ++r) {
            const auto t0 = Clock::now();
            const nmesh::PointCloud c = nmesh::read_points(path);
            seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
            if (c.size() != cloud.size()) throw nmesh::Error(path + ": wrong point count");
        }
        std::FILE* f = std::fopen(path.c_str(), "rb");
        std::fseek(f, 0, SEEK_END);
        const double mb = double(std::ftell(f)) / 1e6;
        std::fclose(f);
        const Summary t = summarize(seconds);
        const double P = double(cloud.size());
        const std::string fmt = report.format == "xyz" ? "xyz" : "ply_binary";
        std::printf(
            "loading %s: %zu points, %.1f MB, %d runs: median %.4f s (min %.4f, max %.4f) = %.1f M points/s "
            "(min %.1f, max %.1f), %.0f MB/s\n",
            fmt.c_str(), cloud.size(), mb, o.runs, t.median, t.min, t.max, P / t.median / 1e6, P / t.max / 1e6,
            P / t.min / 1e6, mb / t.median);
        append_csv(o.csv,
                   format("%s,%zu,%.2f,%d,%.5f,%.5f,%.5f,%.2f,%.2f,%.2f,%.0f\n", fmt.c_str(), cloud.size(), mb, o.runs,
                          t.median, t.min, t.max, P / t.median / 1e6, P / t.max / 1e6, P / t.min / 1e6, mb / t.median));
    }
}

// `pair`: the input-size ratio measured run by run in one process: the base cloud and the cloud
// upsampled to P points reconstructed alternately, R times each, to the same target (finishing
// off). Each pair's ratio (large over small, Statistics::seconds) is taken within seconds of
// itself, so a machine whose speed drifts from one minute to the next (as this one does) skews
// the median ratio far less than it skews two rows timed minutes apart.
void run_pair(const Options& o, const nmesh::PointCloud& small, const nmesh::PointCloud& large) {
    nmesh::Parameters params;
    params.target_vertices = o.vertices;
    params.finish = false;
    std::vector<double> a, b, ratio;
    for (int r = 0; r < o.runs; ++r) {
        a.push_back(nmesh::reconstruct(small, params).stats.seconds);
        b.push_back(nmesh::reconstruct(large, params).stats.seconds);
        ratio.push_back(b.back() / a.back());
    }
    const Summary sa = summarize(a), sb = summarize(b), sr = summarize(ratio);
    std::printf(
        "pair: %zu and %zu points -> %u vertices, %d alternating runs each: median %.3f s (min %.3f, max %.3f) "
        "and %.3f s (min %.3f, max %.3f); ratio per pair median %.2f (min %.2f, max %.2f)\n",
        small.size(), large.size(), o.vertices, o.runs, sa.median, sa.min, sa.max, sb.median, sb.min, sb.max, sr.median,
        sr.min, sr.max);
    append_csv(o.csv, format("%zu,%zu,%u,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f\n", small.size(), large.size(),
                             o.vertices, o.runs, sa.median, sa.min, sa.max, sb.median, sb.min, sb.max, sr.median,
                             sr.min, sr.max));
}

int usage(const char* argv0) {
    std::fprintf(stderr,
                 "usage: %s output|input --vertices N --points P [--runs R] [--cloud FILE] [--csv FILE] [--profile]\n"
                 "       %s loading --points P [--runs R] [--cloud FILE] [--csv FILE]\n"
                 "       %s pair --vertices N --points P [--runs R] [--cloud FILE] [--csv FILE]\n",
                 argv0, argv0, argv0);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage(argv[0]);
    Options o;
    o.mode = argv[1];
    if (o.mode != "output" && o.mode != "input" && o.mode != "loading" && o.mode != "pair") return usage(argv[0]);
    try {
        const nmesh::cli::Arguments args(argc, argv, 2, {"--profile"},
                                         {"--vertices", "--points", "--runs", "--cloud", "--csv"});
        o.vertices = std::uint32_t(args.count("--vertices", o.vertices));
        o.points = args.count("--points", o.points);
        o.runs = int(std::max<std::uint64_t>(1, args.count("--runs", std::uint64_t(o.runs))));
        o.cloud = args.text("--cloud", o.cloud);
        o.csv = args.text("--csv", o.csv);
        o.profile = args.has("--profile");
    } catch (const nmesh::cli::UsageError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return usage(argv[0]);
    }
    try {
        const nmesh::PointCloud base = nmesh::read_points(o.cloud);
        const std::uint32_t k =
            o.points == 0
                ? 1u
                : std::max<std::uint32_t>(1, std::uint32_t(std::llround(double(o.points) / double(base.size()))));
        const auto t0 = Clock::now();
        const nmesh::PointCloud cloud = upsample(base, k);
        std::fprintf(stderr, "cloud: %s x %u = %zu points (generated in %.2f s)\n", o.cloud.c_str(), k, cloud.size(),
                     std::chrono::duration<double>(Clock::now() - t0).count());
        if (o.mode == "loading")
            run_loading(o, cloud);
        else if (o.mode == "pair")
            run_pair(o, base, cloud);
        else
            run_reconstruction(o, cloud, k);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
