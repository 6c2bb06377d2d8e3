// The image display's OpenGL side: an RGBA8 texture and a triangle covering the window.
#include "render/image_display.h"

#include "render/gl.h"

namespace weir {

namespace {

// The triangle (-1, -1), (3, -1), (-1, 3) covers the viewport; texture rows run from the top.
const char* kVertexShader = R"(#version 330 core
out vec2 uv;
void main() {
    vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    uv = vec2(0.5 * (corner.x + 1.0), 0.5 * (1.0 - corner.y));
    gl_Position = vec4(corner, 0.0, 1.0);
}
)";

const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
uniform sampler2D image;
out vec4 colour;
void main() { colour = vec4(texture(image, uv).rgb, 1.0); }
)";

}  // namespace

#if !defined(WEIR_HAS_CUDA)
std::unique_ptr<ImageInterop> makeImageInterop(unsigned, std::string* why) {
    if (why != nullptr) {
        *why = "this weir was built without CUDA";
    }
    return nullptr;
}
#endif

ImageDisplay::ImageDisplay() {
    program_ = buildProgram(kVertexShader, kFragmentShader, "image display");
    glGenVertexArrays(1, &vao_);  // the core profile draws only with a vertex array bound
    checkGl("image display set-up");
}

ImageDisplay::~ImageDisplay() {
    interop_.reset();  // unregistered before the texture goes
    glDeleteTextures(1, &texture_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
}

void ImageDisplay::ensureTexture(int width, int height) {
    if (texture_ != 0 && width == width_ && height == height_) {
        return;
    }
    interop_.reset();
    interopTried_ = false;
    if (texture_ == 0) {
        glGenTextures(1, &texture_);
    }
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    width_ = width;
    height_ = height;
    checkGl("image display texture");
}

bool ImageDisplay::setDeviceImage(const std::uint8_t* deviceRgba, int width, int height,
                                  std::string* why) {
    ensureTexture(width, height);
    if (!interopTried_) {
        interopTried_ = true;
        interop_ = makeImageInterop(texture_, &interopWhy_);
    }
    if (!interop_) {
        if (why != nullptr) {
            *why = interopWhy_;
        }
        return false;
    }
    interop_->copy(deviceRgba, width, height);
    return true;
}

void ImageDisplay::setHostImage(const std::uint8_t* rgb, int width, int height) {
    ensureTexture(width, height);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGl("image display upload");
}

void ImageDisplay::draw(int width, int height) {
    if (texture_ == 0) {
        return;
    }
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glUniform1i(glGetUniformLocation(program_, "image"), 0);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glUseProgram(0);
    glEnable(GL_DEPTH_TEST);
    checkGl("image display draw");
}

}  // namespace weir
