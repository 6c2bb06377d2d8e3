// Fuzzes both OBJ readers: the obstacle reader (scene/mesh_file.h, std::runtime_error naming the
// file) and the surface mesh reader (io/mesh_reader.h, IoError). Other exceptions, crashes and
// sanitizer reports are bugs.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/mesh_reader.h"
#include "scene/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        weir::parseObjMesh(text, "fuzz.obj");
    } catch (const std::runtime_error&) {
    }
    try {
        weir::readObj(weir::fuzz::inputFile(data, size, ".obj"));
    } catch (const weir::IoError&) {
    }
    return 0;
}
