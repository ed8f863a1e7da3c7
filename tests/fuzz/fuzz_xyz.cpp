// libFuzzer harness: text point files through read_points, inspect_file and read_mesh. The first
// byte picks the extension (.xyz .txt .pts .csv, which differ only in the PTS count line); the
// rest is the file.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const char* const kExtensions[] = {".xyz", ".txt", ".pts", ".csv"};
    const nmesh::fuzz::Reading r =
        nmesh::fuzz::read_everything(nmesh::fuzz::write_input(data + 1, size - 1, kExtensions[data[0] & 3]));
    NMESH_FUZZ_REQUIRE(!r.mesh_ok || r.mesh.triangles.empty());  // text point files have no faces
    return 0;
}
