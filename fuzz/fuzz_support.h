// What the harnesses share: the input as a file (the frame and mesh readers take paths), in
// /dev/shm where it exists so that a million executions do not touch a disk.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace weir::fuzz {

// Writes the input to one file per process with the given extension and returns its path.
inline std::string inputFile(const std::uint8_t* data, std::size_t size,
                             const std::string& extension) {
    static const std::string dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
    const std::string path = dir + "/weir_fuzz_" + std::to_string(::getpid()) + extension;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

}  // namespace weir::fuzz
