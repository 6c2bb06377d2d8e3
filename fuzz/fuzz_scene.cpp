// Fuzzes the scene parser (parseScene, scene/scene.h) with arbitrary text. A SceneError is the
// parser doing its job; any other exception, a crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        weir::parseScene(std::string(reinterpret_cast<const char*>(data), size), "<fuzz>");
    } catch (const weir::SceneError&) {
    }
    return 0;
}
