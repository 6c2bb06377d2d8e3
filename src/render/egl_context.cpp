// EGL display selection and context creation.
#include "render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <functional>
#include <vector>

#include "render/gl.h"

namespace weir {

namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) {
        return false;
    }
    const std::size_t n = std::strlen(name);
    for (const char* at = std::strstr(list, name); at != nullptr; at = std::strstr(at + 1, name)) {
        if ((at == list || at[-1] == ' ') && (at[n] == ' ' || at[n] == '\0')) {
            return true;
        }
    }
    return false;
}

std::string eglErrorText() {
    char text[32];
    std::snprintf(text, sizeof text, "EGL error 0x%04x", unsigned(eglGetError()));
    return text;
}

struct Candidate {
    std::string label;
    std::function<EGLDisplay()> open;
};

// The displays to try, best first.
std::vector<Candidate> candidateDisplays() {
    std::vector<Candidate> candidates;
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);  // null: no client exts
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    const bool platformExt =
        getPlatformDisplay != nullptr && (hasExtension(client, "EGL_EXT_platform_base") ||
                                          hasExtension(client, "EGL_EXT_platform_device") ||
                                          hasExtension(client, "EGL_MESA_platform_surfaceless"));

    if (platformExt && queryDevices != nullptr && hasExtension(client, "EGL_EXT_platform_device")) {
        EGLint count = 0;
        if (queryDevices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(std::size_t(count), nullptr);
            queryDevices(count, devices.data(), &count);
            devices.resize(std::size_t(count));
            std::vector<Candidate> software;
            for (std::size_t i = 0; i < devices.size(); ++i) {
                const char* deviceExts = queryDeviceString != nullptr
                                             ? queryDeviceString(devices[i], EGL_EXTENSIONS)
                                             : nullptr;
                const bool isSoftware = hasExtension(deviceExts, "EGL_MESA_device_software");
                EGLDeviceEXT device = devices[i];
                Candidate c{
                    "EGL device " + std::to_string(i) + (isSoftware ? " (software)" : ""),
                    [=] { return getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr); }};
                (isSoftware ? software : candidates).push_back(c);
            }
            candidates.insert(candidates.end(), software.begin(), software.end());
        }
    }
    if (platformExt && hasExtension(client, "EGL_MESA_platform_surfaceless")) {
        candidates.push_back({"EGL surfaceless platform", [=] {
                                  return getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                                            EGL_DEFAULT_DISPLAY, nullptr);
                              }});
    }
    candidates.push_back(
        {"EGL default display", [] { return eglGetDisplay(EGL_DEFAULT_DISPLAY); }});
    return candidates;
}

// GL version as major * 10 + minor, from the current context.
int currentGlVersion() {
    const auto* text = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    int major = 0, minor = 0;
    if (text == nullptr || std::sscanf(text, "%d.%d", &major, &minor) != 2) {
        return 0;
    }
    return major * 10 + minor;
}

}  // namespace

OffscreenContext::OffscreenContext() {
    std::string failures;
    for (const Candidate& candidate : candidateDisplays()) {
        auto fail = [&](const std::string& why) {
            failures += "\n  " + candidate.label + ": " + why;
        };
        EGLDisplay display = candidate.open();
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
            fail("cannot initialize (" + eglErrorText() + ")");
            continue;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            fail("no desktop OpenGL API");
            continue;
        }
        const bool surfaceless =
            hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
        const EGLint configAttributes[] = {EGL_SURFACE_TYPE,
                                           surfaceless ? 0 : EGL_PBUFFER_BIT,
                                           EGL_RENDERABLE_TYPE,
                                           EGL_OPENGL_BIT,
                                           EGL_RED_SIZE,
                                           8,
                                           EGL_GREEN_SIZE,
                                           8,
                                           EGL_BLUE_SIZE,
                                           8,
                                           EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configs = 0;
        if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs < 1) {
            fail("no OpenGL config");
            continue;
        }
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                            3,
                                            EGL_CONTEXT_MINOR_VERSION,
                                            3,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_NONE};
        EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            fail("no OpenGL 3.3 core context (" + eglErrorText() + ")");
            continue;
        }
        EGLSurface surface = EGL_NO_SURFACE;
        if (!surfaceless) {
            const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            surface = eglCreatePbufferSurface(display, config, pbufferAttributes);
        }
        if ((!surfaceless && surface == EGL_NO_SURFACE) ||
            !eglMakeCurrent(display, surface, surface, context)) {
            fail("cannot make the context current (" + eglErrorText() + ")");
            eglDestroyContext(display, context);
            continue;
        }
        if (currentGlVersion() < 33) {
            fail("OpenGL older than 3.3");
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
            continue;
        }
        display_ = display;
        context_ = context;
        surface_ = surface;
        const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        description_ = candidate.label + ": " + (renderer ? renderer : "?") + ", OpenGL " +
                       (version ? version : "?");
        return;
    }
    throw RenderError(
        "no offscreen OpenGL 3.3 context through EGL. On a machine without a GPU install Mesa "
        "(Debian: libegl-mesa0 libgl1-mesa-dri); with an NVIDIA GPU its driver's EGL library. "
        "Attempts:" +
        failures);
}

OffscreenContext::~OffscreenContext() {
    // The display is not terminated: another context of the process may share it.
    if (display_ != nullptr) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        if (surface_ != nullptr) {
            eglDestroySurface(display_, surface_);
        }
    }
}

void OffscreenContext::makeCurrent() const {
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
        throw RenderError("cannot make the EGL context current (" + eglErrorText() + ")");
    }
}

}  // namespace weir
