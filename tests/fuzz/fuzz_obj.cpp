// libFuzzer harness: OBJ and OFF files (the first byte picks which; the rest is the file) through
// read_points, inspect_file and read_mesh; a mesh that reads is written back as OBJ, OFF and PLY
// and must read back bit for bit.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace nmesh;
    if (size == 0) return 0;
    const fuzz::Reading r =
        fuzz::read_everything(fuzz::write_input(data + 1, size - 1, (data[0] & 1) ? ".off" : ".obj"));
    if (r.mesh_ok && !r.mesh.triangles.empty()) {
        fuzz::round_trip(r.mesh, ".obj");
        fuzz::round_trip(r.mesh, ".off");
        fuzz::round_trip(r.mesh, ".ply");
    }
    return 0;
}
