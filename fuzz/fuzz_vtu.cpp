// Fuzzes the .vtu frame reader (io/frame_reader.h) and the position check that `weir render`
// and `weir mesh` apply to what it returns. IoError is a refusal; any other exception, a crash
// or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/frame_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = weir::fuzz::inputFile(data, size, ".vtu");
    double time = 0;
    try {
        const weir::HostParticles particles = weir::readVtu(path, &time);
        weir::checkFramePositions(particles, path);
    } catch (const weir::IoError&) {
    }
    return 0;
}
