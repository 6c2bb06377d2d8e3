// An 8-bit RGB image and its PNG file (libpng's simplified API), written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace weir {

struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // rows top to bottom, 3 bytes per pixel

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3) {}
    const std::uint8_t* pixel(int x, int y) const {
        return rgb.data() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    }
};

// Writes the image as PNG through a temporary beside `path`, renamed over it; throws IoError
// naming the path when it cannot be encoded or written.
void writePng(const std::string& path, const Image& image);
// Reads any PNG as 8-bit RGB; throws IoError naming the path and libpng's reason.
Image readPng(const std::string& path);

}  // namespace weir
