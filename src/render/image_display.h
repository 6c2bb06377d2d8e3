// A finished image drawn over the whole window: the live water look's frames in `weir view`. The
// image (RGBA8, rows from the top) goes into a texture, from CUDA device memory by CUDA-OpenGL
// interop (no copy through the host) or from host memory, and a full-window triangle draws it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace weir {

// Copies a device image into an OpenGL texture registered with CUDA (image_display_cuda.cu).
class ImageInterop {
   public:
    virtual ~ImageInterop() = default;
    virtual void copy(const std::uint8_t* deviceRgba, int width, int height) = 0;
};

// The interop for this texture of the current OpenGL context, or null (and why) where there is
// none: a build without CUDA, or an OpenGL context on another device than CUDA's.
std::unique_ptr<ImageInterop> makeImageInterop(unsigned texture, std::string* why);

class ImageDisplay {
   public:
    // Needs a current OpenGL 3.3 core context; throws RenderError if its shader does not build.
    ImageDisplay();
    ~ImageDisplay();
    ImageDisplay(const ImageDisplay&) = delete;
    ImageDisplay& operator=(const ImageDisplay&) = delete;

    // The image from CUDA device memory (RGBA8); false (and why) where interop is not possible:
    // then download it and call setHostImage.
    bool setDeviceImage(const std::uint8_t* deviceRgba, int width, int height, std::string* why);
    // The image from host memory, 3 bytes (RGB) per pixel.
    void setHostImage(const std::uint8_t* rgb, int width, int height);
    // Draws the image over the bound framebuffer of width x height pixels, scaled to fill it.
    void draw(int width, int height);

   private:
    void ensureTexture(int width, int height);
    unsigned texture_ = 0, program_ = 0, vao_ = 0;
    int width_ = 0, height_ = 0;
    std::unique_ptr<ImageInterop> interop_;
    bool interopTried_ = false;
    std::string interopWhy_;
};

}  // namespace weir
