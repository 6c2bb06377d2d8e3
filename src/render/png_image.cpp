// PNG encoding and decoding with libpng's simplified API (no setjmp in our code).
#include "render/png_image.h"

#include <png.h>

#include <ostream>

#include "io/atomic_file.h"
#include "io/io_error.h"

namespace weir {

void writePng(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3) {
        throw IoError("cannot write '" + path + "': the image is empty or its size is wrong");
    }
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(image.width);
    png.height = png_uint_32(image.height);
    png.format = PNG_FORMAT_RGB;
    const png_int_32 stride = image.width * 3;
    // Encoded once, into a buffer of libpng's bound on the encoded size (asking for the size
    // first would encode twice: half of the time `weir render` spent writing a 1280 x 720 image).
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
    std::vector<std::uint8_t> bytes(size);
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), stride,
                                   nullptr)) {
        bytes.clear();
    }
    if (bytes.empty()) {
        const std::string reason = png.message;
        png_image_free(&png);
        throw IoError("cannot encode '" + path + "' as PNG: " + reason);
    }
    writeFileAtomically(path, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(size));
    });
}

Image readPng(const std::string& path) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) {
        throw IoError("cannot read '" + path + "' as PNG: " + png.message);
    }
    png.format = PNG_FORMAT_RGB;
    Image image(int(png.width), int(png.height));
    if (!png_image_finish_read(&png, nullptr, image.rgb.data(), png_int_32(png.width * 3),
                               nullptr)) {
        const std::string reason = png.message;
        png_image_free(&png);
        throw IoError("cannot read '" + path + "' as PNG: " + reason);
    }
    return image;
}

}  // namespace weir
