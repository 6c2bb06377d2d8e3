// Fuzzes the STL reader of obstacle meshes (scene/mesh_file.h), binary and ASCII: refusals are
// std::runtime_error naming the file; other exceptions, crashes and sanitizer reports are bugs.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "scene/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        weir::parseStlMesh(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.stl");
    } catch (const std::runtime_error&) {
    }
    return 0;
}
