// Shared by the libFuzzer harnesses of the readers. The readers take a path, so each input is
// written to a scratch file first; every call must either succeed with a self-consistent result
// or throw nmesh::IoError. Anything else (another exception, a sanitizer report, a failed check
// below, an allocation beyond libFuzzer's -malloc_limit_mb) is a finding.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/io.h"

namespace nmesh::fuzz {

// Aborts with a message: libFuzzer records the input as a crash.
[[noreturn]] inline void finding(const char* what, const std::string& detail = {}) {
    std::fprintf(stderr, "fuzz finding: %s %s\n", what, detail.c_str());
    std::abort();
}

#define NMESH_FUZZ_REQUIRE(cond)                                     \
    do {                                                             \
        if (!(cond)) ::nmesh::fuzz::finding("check failed:", #cond); \
    } while (0)

// A scratch file name in $TMPDIR (or /tmp), one per process and extension.
inline std::string scratch_path(const std::string& extension) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/nmesh_fuzz_" + std::to_string(::getpid()) + extension;
}

// The scratch files of this process, removed when it exits normally (libFuzzer's -runs and
// -max_total_time end with exit(); after a crash they stay, beside the reproducer).
class ScratchFiles {
public:
    ScratchFiles() = default;
    ScratchFiles(const ScratchFiles&) = delete;
    ScratchFiles& operator=(const ScratchFiles&) = delete;
    ~ScratchFiles() {
        for (const std::string& p : paths_) std::remove(p.c_str());
    }
    void add(const std::string& path) {
        for (const std::string& p : paths_)
            if (p == path) return;
        paths_.push_back(path);
    }

private:
    std::vector<std::string> paths_;
};

inline void remember_scratch(const std::string& path) {
    static ScratchFiles files;
    files.add(path);
}

// Writes the input to the scratch file for `extension`; returns its path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    const std::string path = scratch_path(extension);
    remember_scratch(path);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) finding("cannot create the scratch file", path);
    if (size > 0 && std::fwrite(data, 1, size, f) != size) finding("cannot write the scratch file", path);
    std::fclose(f);
    return path;
}

inline bool finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

inline bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

// What the three readers made of one file.
struct Reading {
    bool points_ok = false, info_ok = false, mesh_ok = false;
    PointCloud cloud;
    PointReadReport report;
    FileInfo info;
    IndexedMesh mesh;
};

// read_points, inspect_file and read_mesh on one file, and what each promises about the others.
inline Reading read_everything(const std::string& path) {
    Reading r;
    bool& points_ok = r.points_ok;
    bool& info_ok = r.info_ok;
    bool& mesh_ok = r.mesh_ok;
    PointCloud& cloud = r.cloud;
    PointReadReport& report = r.report;
    FileInfo& info = r.info;
    IndexedMesh& mesh = r.mesh;
    try {
        cloud = read_points(path, &report);
        points_ok = true;
    } catch (const IoError&) {
    }
    try {
        info = inspect_file(path);
        info_ok = true;
    } catch (const IoError&) {
    }
    try {
        mesh = read_mesh(path);
        mesh_ok = true;
    } catch (const IoError&) {
    }
    // inspect_file reports every error read_points reports.
    NMESH_FUZZ_REQUIRE(points_ok || !info_ok);
    if (points_ok) {
        NMESH_FUZZ_REQUIRE(report.points_read == cloud.size());
        for (const Vec3& p : cloud.points) NMESH_FUZZ_REQUIRE(finite(p));
    }
    if (points_ok && info_ok) {
        NMESH_FUZZ_REQUIRE(info.points == cloud.size());
        NMESH_FUZZ_REQUIRE(info.non_finite == report.non_finite_dropped);
        // The bounding box is that of the finite points, exactly.
        const BoundingBox box = bounding_box(cloud.points);
        NMESH_FUZZ_REQUIRE(info.bounds.empty() == cloud.empty());
        if (!cloud.empty())
            NMESH_FUZZ_REQUIRE(same_bits(info.bounds.min, box.min) && same_bits(info.bounds.max, box.max));
    }
    if (mesh_ok) {
        for (const Vec3& p : mesh.positions) NMESH_FUZZ_REQUIRE(finite(p));
        for (const auto& t : mesh.triangles)
            for (std::uint32_t i : t) NMESH_FUZZ_REQUIRE(i < mesh.positions.size());
        // read_mesh keeps every vertex and refuses non-finite ones: the same points as read_points.
        NMESH_FUZZ_REQUIRE(points_ok);
        NMESH_FUZZ_REQUIRE(mesh.positions.size() == cloud.size());
        for (std::size_t i = 0; i < cloud.size(); ++i)
            NMESH_FUZZ_REQUIRE(same_bits(mesh.positions[i], cloud.points[i]));
        // inspect_file gives the topology of the same triangles.
        NMESH_FUZZ_REQUIRE(info_ok && info.topology_error.empty());
        NMESH_FUZZ_REQUIRE(info.topology.has_value() == !mesh.triangles.empty());
        if (info.topology) {
            const MeshTopology t = mesh_topology(mesh);
            NMESH_FUZZ_REQUIRE(t.euler == info.topology->euler && t.genus == info.topology->genus);
            NMESH_FUZZ_REQUIRE(t.boundary_loops == info.topology->boundary_loops);
        }
    }
    return r;
}

// A mesh read back from `extension` after write_mesh is the same mesh, bit for bit.
inline void round_trip(const IndexedMesh& mesh, const std::string& extension, bool ply_ascii = false) {
    const std::string path = scratch_path("_out" + extension);
    remember_scratch(path);
    MeshWriteOptions options;
    options.ply_ascii = ply_ascii;
    write_mesh(path, mesh, options);
    const IndexedMesh back = read_mesh(path);
    NMESH_FUZZ_REQUIRE(back.positions.size() == mesh.positions.size());
    NMESH_FUZZ_REQUIRE(back.triangles == mesh.triangles);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        NMESH_FUZZ_REQUIRE(same_bits(back.positions[i], mesh.positions[i]));
}

}  // namespace nmesh::fuzz
