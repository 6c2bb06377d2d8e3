// A headless OpenGL 3.3 core context through EGL, for images without a window: the GPU's driver
// (NVIDIA's EGL) where one is present, Mesa's llvmpipe software renderer otherwise.
#pragma once

#include <string>

namespace weir {

class OffscreenContext {
   public:
    // Tries, in order: each EGL device (EGL_EXT_platform_device; hardware before software), Mesa's
    // surfaceless platform, the default display. The first that gives a 3.3 core context is made
    // current. Throws RenderError listing why each attempt failed.
    OffscreenContext();
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    // Makes this context current on the calling thread again.
    void makeCurrent() const;
    // How the context was made and what renders, e.g. "EGL device 0: NVIDIA H100 ... (4.6 ...)".
    const std::string& description() const { return description_; }

   private:
    void* display_ = nullptr;
    void* context_ = nullptr;
    void* surface_ = nullptr;
    std::string description_;
};

}  // namespace weir
