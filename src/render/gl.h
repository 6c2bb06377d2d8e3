// OpenGL 3.3 core declarations. Functions are linked from GLVND's libOpenGL, which dispatches to
// whichever context (EGL offscreen or GLX through GLFW) is current, so no loader is needed.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <stdexcept>
#include <string>

namespace weir {

// A rendering failure: no EGL display or context, a shader that does not compile, an unwritable
// image.
class RenderError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

// Throws RenderError naming `what` if the GL error flag is set.
void checkGl(const char* what);

// A linked program of a vertex and a fragment shader (GLSL source); throws RenderError naming
// `name` with the compiler's or linker's log if either fails.
GLuint buildProgram(const std::string& vertex, const std::string& fragment, const char* name);

}  // namespace weir
