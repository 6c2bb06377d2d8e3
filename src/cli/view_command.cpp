// `weir view`: a GLFW window that simulates a scene and draws it as it runs, with keys to pause,
// step, reset and switch colouring or particles/surface, the mouse to orbit, pan and zoom, and a
// line of statistics on screen.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "core/backend.h"
#include "render/gl.h"  // before GLFW, which then includes no GL header of its own
#include "solver/simulation.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "cli/render_commands.h"
#include "cli/video.h"
#include "raytrace/interactive_water.h"
#include "render/image_display.h"
#include "render/particle_interop.h"
#include "render/png_image.h"
#include "render/renderer.h"
#include "scene/setup.h"
#include "surface/surface.h"

namespace weir {

namespace {

using Clock = std::chrono::steady_clock;

// The frame rate of --record's video: one drawn frame per video frame.
constexpr int kRecordFps = 30;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string fixed(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// The keys of --press: names as the help lists them.
int keyCode(const std::string& name) {
    static const std::pair<const char*, int> kKeys[] = {
        {"space", GLFW_KEY_SPACE}, {"s", GLFW_KEY_S},           {"r", GLFW_KEY_R},
        {"c", GLFW_KEY_C},         {"m", GLFW_KEY_M},           {"f", GLFW_KEY_F},
        {"q", GLFW_KEY_Q},         {"left", GLFW_KEY_LEFT},     {"right", GLFW_KEY_RIGHT},
        {"up", GLFW_KEY_UP},       {"down", GLFW_KEY_DOWN},     {"plus", GLFW_KEY_EQUAL},
        {"minus", GLFW_KEY_MINUS}, {"escape", GLFW_KEY_ESCAPE}, {"w", GLFW_KEY_W}};
    for (const auto& [keyName, code] : kKeys) {
        if (name == keyName) {
            return code;
        }
    }
    throw std::invalid_argument(
        "--press: '" + name +
        "' is not a key; allowed: space, s, r, c, m, w, f, q, left, right, up, down, plus, "
        "minus, escape, or 'none' for a frame without a key");
}

std::vector<int> parseKeys(const std::string& list) {
    std::vector<int> keys;
    std::stringstream in(list);
    for (std::string item; std::getline(in, item, ',');) {
        keys.push_back(item == "none" || item.empty() ? 0 : keyCode(item));
    }
    return keys;
}

// Everything the window's callbacks change.
class Viewer {
   public:
    Viewer(const ViewOptions& options, Scene scene)
        : options_(options),
          scene_(std::move(scene)),
          backend_(parseBackend(options.backend)),
          field_(parseColourField(options.color)) {}

    void open() {
        glfwSetErrorCallback([](int code, const char* text) {
            std::fprintf(stderr, "weir: GLFW error 0x%x: %s\n", code, text);
        });
        if (!glfwInit()) {
            throw RenderError(
                "cannot open a window: GLFW found no display (is DISPLAY set? on a machine "
                "without one, run under xvfb-run, or use `weir render` for offscreen images)");
        }
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_SAMPLES, 4);
        window_ = glfwCreateWindow(options_.width, options_.height,
                                   ("weir view: " + scene_.name).c_str(), nullptr, nullptr);
        if (window_ == nullptr) {
            glfwTerminate();
            throw RenderError(
                "cannot open a window with an OpenGL 3.3 core context (the display's OpenGL is "
                "older, or GLX is missing); `weir render` draws offscreen through EGL instead");
        }
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(options_.maxFrames > 0 ? 0 : 1);
        glfwSetWindowUserPointer(window_, this);
        glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
            if (action == GLFW_PRESS || action == GLFW_REPEAT) {
                static_cast<Viewer*>(glfwGetWindowUserPointer(w))->press(key);
            }
        });
        glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->mouseButton(button, action, mods);
        });
        glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->mouseMove(x, y);
        });
        glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
            static_cast<Viewer*>(glfwGetWindowUserPointer(w))->camera_.zoom(std::pow(0.9, dy));
        });
        renderer_ = std::make_unique<Renderer>();
        renderer_->setGeometry(SceneGeometry::of(scene_));
        const auto* glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        glRenderer_ = glRenderer != nullptr ? glRenderer : "?";
        frameCamera();
        if (!options_.camera.empty() || !options_.target.empty()) {
            camera_ =
                commandLineCamera(scene_.container, aspect(), options_.camera, options_.target);
        }
    }

    void close() {
        interop_.reset();
        water_.reset();
        imageDisplay_.reset();  // with the OpenGL context still current
        renderer_.reset();
        if (window_ != nullptr) {
            glfwDestroyWindow(window_);
            window_ = nullptr;
        }
        glfwTerminate();
    }

    // (Re)builds the simulation from the scene: start and the R key.
    void reset() {
        SetupOptions setupOptions;
        setupOptions.particleCount = options_.particles;
        SimulationSetup setup = buildSetup(scene_, setupOptions, &report_);
        const NeighbourMode mode =
            resolveNeighbourMode(parseNeighbourMode(options_.neighbours), setup.grid,
                                 std::int64_t(setup.particles.size()));
        interop_.reset();  // before the solver whose arrays it reads
        sim_.reset();
        sim_ = makeSimulation(backend_, mode, std::move(setup));
        sim_->computeDensity();
        stepsPerDraw_ = 1;
        stepWindow_.clear();
        status_.clear();
        blewUp_ = false;
        interop_ = makeParticleInterop(*sim_, &interopWhy_);
        applyColourRange();
        upload();
    }

    void run() {
        const std::vector<int> pressed = parseKeys(options_.press);
        std::cerr << "weir: viewing " << scene_.name << ": " << sim_->particleCount()
                  << " particles on " << backendName(backend_) << " (" << sim_->deviceName()
                  << "), drawn by " << glRenderer_ << ", particles by "
                  << (interop_ ? interop_->description() : "host copy (" + interopWhy_ + ")")
                  << "\n"
                  << "weir: keys: space pause, s step, r reset, c colour, m particles/surface, "
                     "w water look, f frame, q quit; mouse: left orbit, right pan, wheel zoom\n";
        if (!options_.record.empty()) {
            int w = 0, h = 0;
            glfwGetFramebufferSize(window_, &w, &h);
            recorder_ = std::make_unique<VideoRecorder>(options_.record, w, h, kRecordFps);
            std::cerr << "weir: recording every frame drawn to " << options_.record << " (" << w
                      << "x" << h << ", " << kRecordFps << " frames/s)\n";
        }
        const auto start = Clock::now();
        while (!glfwWindowShouldClose(window_)) {
            if (drawn_ < std::int64_t(pressed.size()) && pressed[std::size_t(drawn_)] != 0) {
                press(pressed[std::size_t(drawn_)]);
            }
            if (!paused_) {
                simulate(stepsPerDraw_);
            }
            draw();
            record();
            glfwSwapBuffers(window_);
            frameTimes_.push_back(Clock::now());
            while (frameTimes_.size() > 31) {
                frameTimes_.pop_front();
            }
            glfwPollEvents();
            ++drawn_;
            if (options_.maxFrames > 0 && drawn_ >= options_.maxFrames) {
                break;
            }
        }
        const double seconds = secondsSince(start);
        if (recorder_) {
            recorder_->finish();
            std::cerr << "weir: video " << options_.record << ": " << recorder_->frames()
                      << " frames (H.264, " << kRecordFps << " frames/s)\n";
        }
        std::cerr << "weir: view closed after " << drawn_ << " frames in " << fixed(seconds, 1)
                  << " s (" << fixed(seconds > 0 ? double(drawn_) / seconds : 0, 1)
                  << " frames/s); last lines: " << statsLine() << "; " << stagesLine() << "\n";
    }

   private:
    double aspect() const {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        return h > 0 ? double(w) / h : double(options_.width) / options_.height;
    }

    void frameCamera() { camera_ = frameBox(scene_.container, aspect()); }

    void applyColourRange() {
        const double g = length(scene_.gravity);
        renderer_->setColourRange(physicalRange(field_, scene_.restDensity, report_.expectedSpeed,
                                                scene_.restDensity * g * report_.fluidHeight));
    }

    // Advances `steps` steps, the last one timed per stage; stops at a fault.
    void simulate(int steps) {
        if (blewUp_) {
            return;  // only R brings it back
        }
        const auto t0 = Clock::now();
        if (steps > 1) {
            sim_->advance(steps - 1);
        }
        sim_->setTiming(true);
        sim_->advance(1);
        sim_->synchronize();
        sim_->setTiming(false);
        const double seconds = secondsSince(t0);
        stepWindow_.push_back({steps, seconds});
        while (stepWindow_.size() > 30) {
            stepWindow_.pop_front();
        }
        // Simulate about 25 ms per drawn frame, so that the window stays responsive, and no
        // faster than real time, so that the fluid moves at its true speed where it can.
        const double perStep = seconds / steps;
        const double frameSeconds = lastDraw_.time_since_epoch().count() == 0
                                        ? 1.0 / 60
                                        : std::min(secondsSince(lastDraw_), 0.1);
        lastDraw_ = Clock::now();
        const double realTimeSteps = frameSeconds / double(sim_->params().timeStep);
        // The water look's frame costs its own time on the GPU: the simulation gets what is left
        // of about 30 ms (at least 3 ms).
        const double budget = waterLook_ ? std::max(0.003, 0.030 - waterMs_ / 1000) : 0.025;
        const int wanted =
            int(std::clamp(std::min(budget / std::max(perStep, 1e-7), std::max(realTimeSteps, 1.0)),
                           1.0, 10000.0));
        stepsPerDraw_ = std::clamp(wanted, stepsPerDraw_ / 2, stepsPerDraw_ * 2 + 1);
        const StageTimes& times = sim_->stageTimes();
        for (const auto& [stage, samples] : times.samples()) {
            stageMs_[stage] = times.median(stage);
        }
        if (!times.samples().empty() && times.samples().begin()->second.size() > 60) {
            sim_->clearStageTimes();
        }
        const FaultRecord fault = sim_->fault();
        if (fault.code != 0) {
            blewUp_ = true;
            status_ = "BLEW UP (r resets): " + describeFault(fault, sim_->params());
            std::cerr << "weir: " << status_ << "\n";
            paused_ = true;
        }
        upload();
    }

    // The particles (and the surface in surface mode) to the renderer; in the water look, to it
    // instead (from the GPU where the simulation runs there, else from a host copy).
    void upload() {
        const auto t0 = Clock::now();
        if (waterLook_) {
            const ParticleArrays arrays = sim_->particleArrays();
            if (arrays.onDevice) {
                water_->setParticles(arrays.pos, arrays.count);
            } else {
                sim_->download(host_);
                water_->setHostParticles(host_);
            }
            if (!scene_.bodies.empty()) {
                std::vector<BodyPose> poses;
                for (const RigidBody& b : sim_->rigidBodies()) {
                    poses.push_back(poseOf(b));
                }
                water_->setBodyPoses(poses);
            }
            uploadMs_ = 1000 * secondsSince(t0);
            return;
        }
        if (interop_ && mode_ == RenderMode::Particles) {
            interop_->update(*renderer_, field_, 0.5 * report_.spacing);
            if (!scene_.bodies.empty()) {  // the particles stay on the GPU; the poses come back
                std::vector<BodyPose> poses;
                for (const RigidBody& b : sim_->rigidBodies()) {
                    poses.push_back(poseOf(b));
                }
                renderer_->setBodies(scene_.bodies, poses);
            }
        } else {
            sim_->download(host_);
            renderer_->setParticles(host_, field_, 0.5 * report_.spacing);
            renderer_->setBodies(scene_.bodies, host_.bodies);
        }
        uploadMs_ = 1000 * secondsSince(t0);
        if (mode_ == RenderMode::Surface) {
            const auto m0 = Clock::now();
            SurfaceOptions options;
            options.spacing = report_.spacing;
            try {
                renderer_->setMesh(reconstructSurface(backend_, host_, options));
                meshMs_ = 1000 * secondsSince(m0);
            } catch (const std::exception& e) {
                status_ = std::string("no surface: ") + e.what();
                mode_ = RenderMode::Particles;
                renderer_->setMode(mode_);
            }
        }
    }

    std::string statsLine() const {
        double steps = 0, seconds = 0;
        for (const auto& [n, s] : stepWindow_) {
            steps += n;
            seconds += s;
        }
        std::string line = std::to_string(sim_->particleCount()) + " particles  " +
                           fixed(seconds > 0 ? steps / seconds : 0, 0) + " steps/s  t " +
                           fixed(sim_->time(), 3) + " s  " + fixed(framesPerSecond(), 1) +
                           " frames/s" + (paused_ ? "  PAUSED" : "");
        return line;
    }

    // Over the last 30 frames drawn.
    double framesPerSecond() const {
        if (frameTimes_.size() < 2) {
            return 0;
        }
        const double seconds =
            std::chrono::duration<double>(frameTimes_.back() - frameTimes_.front()).count();
        return seconds > 0 ? double(frameTimes_.size() - 1) / seconds : 0;
    }

    std::string stagesLine() const {
        std::string line;
        double total = 0;
        for (const char* stage : {"grid", "density", "force", "integrate"}) {
            const auto it = stageMs_.find(stage);
            const double ms = it != stageMs_.end() ? it->second : 0;
            total += ms;
            line += std::string(stage) + " " + fixed(ms, 2) + "  ";
        }
        line += "step " + fixed(total, 2) + " ms  copy " + fixed(uploadMs_, 1) + " ms";
        if (waterLook_) {
            const InteractiveWaterTimes& t = water_->times();
            line += "  surface " + fixed(t.surfaceMs, 1) + "  bvh " + fixed(t.bvhMs, 1) +
                    "  trace " + fixed(t.traceMs, 1) + " ms  " +
                    std::to_string(water_->pathsPerPixel()) + " paths/px";
        } else if (mode_ == RenderMode::Surface) {
            line += "  surface " + fixed(meshMs_, 0) + " ms";
        }
        return line;
    }

    void draw() {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w <= 0 || h <= 0) {
            return;  // minimised
        }
        if (waterLook_) {
            drawWater(w, h);  // first: its times go into the lines
        }
        std::vector<std::string> lines = {
            statsLine(), stagesLine(),
            waterLook_ ? std::string("water look  ") + backendName(backend_) + "  " +
                             std::to_string(w) + "x" + std::to_string(h) + "  " + waterDisplay_
                       : std::string(colourFieldName(field_)) + "  " + backendName(backend_) +
                             "  " + (mode_ == RenderMode::Surface ? "surface" : "particles")};
        if (!status_.empty()) {
            lines.push_back(status_);
        }
        renderer_->setOverlayText(lines);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (waterLook_) {
            imageDisplay_->draw(w, h);
            renderer_->drawOverlayOnly(w, h);
        } else {
            renderer_->draw(camera_, w, h);
        }
        if (!options_.screenshot.empty() && options_.maxFrames > 0 &&
            drawn_ + 1 == options_.maxFrames) {
            writePng(options_.screenshot, readWindow(w, h));
        }
    }

    // The live water look: the camera and window size given, one more frame traced (the paths
    // accumulate while nothing moves), the image to the window's texture, by interop where the
    // window's OpenGL runs on the CUDA device, else through the host.
    void drawWater(int w, int h) {
        const auto t0 = Clock::now();
        try {
            PinholeCamera camera;
            camera.eye = Vec3f(camera_.eye());
            camera.forward = Vec3f(camera_.forward());
            camera.right = Vec3f(camera_.right());
            camera.up = Vec3f(camera_.up());
            camera.tanHalfFovY = float(std::tan(0.5 * camera_.fovY * 3.14159265358979323846 / 180));
            water_->resize(w, h);
            water_->setCamera(camera);
            // Paused, the frame's time goes to refining: as many paths per pixel as about 20 ms
            // of the last frame's trace allows (up to 32).
            const InteractiveWaterTimes& last = water_->times();
            const double msPerPath = last.paths > 0 ? last.traceMs / last.paths : 0;
            water_->setPathsPerFrame(
                paused_ ? std::clamp(int(20.0 / std::max(msPerPath, 0.5)), 1, 32) : 1);
            water_->render();
            std::string why;
            if (imageDisplay_->setDeviceImage(water_->deviceRgba(), w, h, &why)) {
                waterDisplay_ = "shown by CUDA-OpenGL interop";
            } else {
                imageDisplay_->setHostImage(water_->rgb().data(), w, h);
                waterDisplay_ = "shown through the host (" + why + ")";
            }
        } catch (const std::exception& e) {
            status_ = std::string("no water look: ") + e.what();
            std::cerr << "weir: " << status_ << "\n";
            setWaterLook(false);
        }
        waterMs_ = 1000 * secondsSince(t0);
    }

    // The W key: the live water look on or off. It runs on a CUDA device (the simulation's, or
    // any where the simulation runs on the CPU); without one the status line says so.
    void setWaterLook(bool on) {
        if (on && !water_) {
            std::string why;
            if (!interactiveWaterAvailable(&why)) {
                status_ = "the water look needs a CUDA GPU: " + why;
                std::cerr << "weir: " << status_ << "\n";
                return;
            }
            int w = 0, h = 0;
            glfwGetFramebufferSize(window_, &w, &h);
            try {
                water_ = std::make_unique<InteractiveWater>(interactiveWaterSetupOf(
                    scene_, report_.spacing, std::max(w, 16), std::max(h, 16), 1));
                imageDisplay_ = std::make_unique<ImageDisplay>();
            } catch (const std::exception& e) {
                status_ = std::string("no water look: ") + e.what();
                std::cerr << "weir: " << status_ << "\n";
                water_.reset();
                return;
            }
            std::cerr << "weir: water look on: surface, hierarchy and paths on the GPU\n";
        }
        waterLook_ = on;
        renderer_->setShowLegend(!on);
        upload();
    }

    // With --record: the frame just drawn to the video, at the size the recording started with
    // (a resized window is cropped or padded with black).
    void record() {
        if (!recorder_) {
            return;
        }
        int w = 0, h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w <= 0 || h <= 0) {
            return;  // minimised: nothing drawn
        }
        const Image image = readWindow(w, h);
        const int rw = recorder_->width(), rh = recorder_->height();
        if (w == rw && h == rh) {
            recorder_->add(image.rgb);
            return;
        }
        std::vector<std::uint8_t> frame(std::size_t(rw) * std::size_t(rh) * 3, 0);
        for (int y = 0; y < std::min(h, rh); ++y) {
            std::copy_n(&image.rgb[std::size_t(y) * std::size_t(w) * 3],
                        std::size_t(std::min(w, rw)) * 3,
                        &frame[std::size_t(y) * std::size_t(rw) * 3]);
        }
        recorder_->add(frame);
    }

    // The window's back buffer as an image (before the swap).
    static Image readWindow(int w, int h) {
        std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        checkGl("reading the window");
        Image image(w, h);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::uint8_t* src = &rgba[(std::size_t(h - 1 - y) * std::size_t(w) + x) * 4];
                std::uint8_t* dst = &image.rgb[(std::size_t(y) * std::size_t(w) + x) * 3];
                dst[0] = src[0];
                dst[1] = src[1];
                dst[2] = src[2];
            }
        }
        return image;
    }

    void press(int key) {
        switch (key) {
            case GLFW_KEY_SPACE:
                paused_ = !paused_;
                break;
            case GLFW_KEY_S:  // one time step, paused
                paused_ = true;
                simulate(1);
                break;
            case GLFW_KEY_R:
                reset();
                break;
            case GLFW_KEY_C:
                field_ = nextColourField(field_);
                upload();
                applyColourRange();  // after the upload, which takes the new field's own range
                break;
            case GLFW_KEY_M:
                mode_ =
                    mode_ == RenderMode::Particles ? RenderMode::Surface : RenderMode::Particles;
                renderer_->setMode(mode_);
                upload();
                break;
            case GLFW_KEY_W:
                setWaterLook(!waterLook_);
                break;
            case GLFW_KEY_F:
                frameCamera();
                break;
            case GLFW_KEY_LEFT:
                camera_.orbit(-5, 0);
                break;
            case GLFW_KEY_RIGHT:
                camera_.orbit(5, 0);
                break;
            case GLFW_KEY_UP:
                camera_.orbit(0, 5);
                break;
            case GLFW_KEY_DOWN:
                camera_.orbit(0, -5);
                break;
            case GLFW_KEY_EQUAL:
            case GLFW_KEY_KP_ADD:
                camera_.zoom(0.9);
                break;
            case GLFW_KEY_MINUS:
            case GLFW_KEY_KP_SUBTRACT:
                camera_.zoom(1 / 0.9);
                break;
            case GLFW_KEY_Q:
            case GLFW_KEY_ESCAPE:
                glfwSetWindowShouldClose(window_, GLFW_TRUE);
                break;
            default:
                break;
        }
    }

    void mouseButton(int button, int action, int mods) {
        if (action == GLFW_PRESS) {
            dragButton_ = (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT) != 0)
                              ? GLFW_MOUSE_BUTTON_RIGHT
                              : button;
            glfwGetCursorPos(window_, &lastX_, &lastY_);
        } else if (action == GLFW_RELEASE) {
            dragButton_ = -1;
        }
    }

    void mouseMove(double x, double y) {
        const double dx = x - lastX_, dy = y - lastY_;
        lastX_ = x;
        lastY_ = y;
        int w = 0, h = 0;
        glfwGetWindowSize(window_, &w, &h);
        if (h <= 0) {
            return;
        }
        if (dragButton_ == GLFW_MOUSE_BUTTON_LEFT) {
            camera_.orbit(-0.3 * dx, 0.3 * dy);
        } else if (dragButton_ == GLFW_MOUSE_BUTTON_RIGHT ||
                   dragButton_ == GLFW_MOUSE_BUTTON_MIDDLE) {
            camera_.pan(-dx / h, dy / h);
        }
    }

    ViewOptions options_;
    Scene scene_;
    Backend backend_;
    ColourField field_;
    RenderMode mode_ = RenderMode::Particles;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<Simulation> sim_;
    std::unique_ptr<ParticleInterop> interop_;  // null: particles copied through the host
    std::unique_ptr<InteractiveWater> water_;   // the live water look, made by its first W
    std::unique_ptr<ImageDisplay> imageDisplay_;
    bool waterLook_ = false;
    double waterMs_ = 0;                       // the last water frame: trace, display and the rest
    std::string waterDisplay_;                 // how its image reaches the window
    std::unique_ptr<VideoRecorder> recorder_;  // --record
    std::string interopWhy_;                   // why there is no interop
    SetupReport report_;
    HostParticles host_;
    OrbitCamera camera_;
    std::string glRenderer_;
    bool paused_ = false;
    int stepsPerDraw_ = 1;
    Clock::time_point lastDraw_{};
    std::deque<std::pair<int, double>> stepWindow_;  // (steps, seconds) of recent draws
    std::deque<Clock::time_point> frameTimes_;       // when recent frames were shown
    std::map<std::string, double> stageMs_;
    double uploadMs_ = 0, meshMs_ = 0;
    std::string status_;  // a line of warning under the statistics
    bool blewUp_ = false;
    std::int64_t drawn_ = 0;
    int dragButton_ = -1;
    double lastX_ = 0, lastY_ = 0;
};

}  // namespace

int viewCommand(const ViewOptions& options) {
    try {
        if (options.width < 16 || options.width > 16384 || options.height < 16 ||
            options.height > 16384) {
            throw std::invalid_argument("--width " + std::to_string(options.width) + " --height " +
                                        std::to_string(options.height) +
                                        ": each must be within 16..16384 pixels");
        }
        parseColourField(options.color);
        parseKeys(options.press);
        if (!options.screenshot.empty() && options.maxFrames <= 0) {
            throw std::invalid_argument("--screenshot needs --max-frames: it saves the last frame");
        }
        if (!options.record.empty()) {
            checkVideoOutput("--record", options.record);  // before a window opens
        }
        Viewer viewer(options, resolveScene(options.scene));
        struct Closer {
            Viewer& v;
            ~Closer() { v.close(); }
        } closer{viewer};
        viewer.open();
        viewer.reset();
        viewer.run();
        return kExitOk;
    } catch (...) {
        return reportCaughtError();
    }
}

}  // namespace weir
