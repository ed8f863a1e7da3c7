// libFuzzer harness: PLY files (every encoding, header and body) through read_points,
// inspect_file and read_mesh; the same bytes under an unknown extension must be sniffed as PLY
// and read the same; a mesh that reads is written back in binary and ASCII PLY and must read back
// bit for bit.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace nmesh;
    const fuzz::Reading r = fuzz::read_everything(fuzz::write_input(data, size, ".ply"));
    const bool ply_magic =
        (size >= 4 && std::memcmp(data, "ply\n", 4) == 0) || (size >= 5 && std::memcmp(data, "ply\r\n", 5) == 0);
    if (ply_magic) {
        bool sniffed_ok = false;
        PointCloud sniffed;
        try {
            sniffed = read_points(fuzz::write_input(data, size, ".dat"));
            sniffed_ok = true;
        } catch (const IoError&) {
        }
        NMESH_FUZZ_REQUIRE(sniffed_ok == r.points_ok);
        NMESH_FUZZ_REQUIRE(sniffed.size() == r.cloud.size());
        for (std::size_t i = 0; i < sniffed.size(); ++i)
            NMESH_FUZZ_REQUIRE(fuzz::same_bits(sniffed.points[i], r.cloud.points[i]));
    }
    if (r.mesh_ok && !r.mesh.triangles.empty()) {
        fuzz::round_trip(r.mesh, ".ply");
        fuzz::round_trip(r.mesh, ".ply", true);
    }
    return 0;
}
