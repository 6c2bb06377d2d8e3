// Fuzzes the .ply frame reader (io/frame_reader.h) and the position check that `weir render`
// and `weir mesh` apply to what it returns. IoError is a refusal; any other exception, a crash
// or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/frame_reader.h"
#include "io/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = weir::fuzz::inputFile(data, size, ".ply");
    try {
        const weir::HostParticles particles = weir::readPly(path);
        weir::checkFramePositions(particles, path);
    } catch (const weir::IoError&) {
    }
    try {  // the binary PLY surface meshes that weir mesh writes share the header syntax
        weir::readMeshPly(path);
    } catch (const weir::IoError&) {
    }
    return 0;
}
