// The weir subcommands, each a function from parsed options to an exit code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace weir {

// Exit codes shared by all commands.
constexpr int kExitOk = 0;
constexpr int kExitError = 1;     // bad scene, I/O failure, not enough memory
constexpr int kExitUsage = 2;     // bad command-line arguments
constexpr int kExitBlowUp = 3;    // the simulation blew up; frames already written stay
constexpr int kExitValidationFailed = 4;  // weir validate: a check missed its tolerance

struct RunOptions {
    std::string scene;  // file path or built-in name; empty: the built-in dam break
    std::string backend = "auto";
    std::string neighbours = "auto";
    std::optional<std::int64_t> particles;
    std::optional<std::int64_t> frames;
    std::string outDir;  // empty: out/<scene name>
    std::string format = "vtu";
    bool explain = false;
    bool quiet = false;
    bool render = false;  // also render each frame to <out>/images/ (weir_render)
};

struct BenchOptions {
    std::string scene;                   // file or built-in name; empty: dam break
    std::string sizes = "10k,50k";       // particle counts, k/M suffixes allowed
    std::string columns = "auto";        // cpu-brute,cpu-grid,...,cuda-dense or auto
    int steps = 20;                      // timed steps (median per stage)
    int warmup = 3;                      // untimed steps before timing
    double settle = 0.1;                 // simulated seconds before timing: a fluid in motion
    double budget = 60;                  // seconds per (size, column); longer runs are skipped
    std::string outDir = "bench-out";
    bool noPlot = false;
};

struct ValidateOptions {
    std::string backend = "auto";
    int tankResolution = 15;    // particles over the tank's water depth
    int columnResolution = 12;  // particles across the dam-break column
    double damEndT = 5.0;       // dimensionless end time T = t sqrt(2 g / a)
    std::string outDir = "validate-out";
    bool noPlot = false;
};

// `weir render` and `weir view` (src/render/, built when its libraries are found).
struct RenderOptions {
    std::string framesDir;
    std::string outDir;  // empty: <framesDir>/images
    int width = 1280;
    int height = 720;
    std::string color = "speed";
    std::string camera;  // "yaw,pitch,distance"; empty: framed on the container
    std::string target;  // "x,y,z"; empty: the container's centre
    std::string scene;   // scene whose container and obstacles are drawn; empty: none
    std::string video;   // an .mp4 made from the images with ffmpeg; empty: none
    bool surface = false;
    int samples = 4;
    bool quiet = false;
};

struct ViewOptions {
    std::string scene;
    std::string backend = "auto";
    std::string neighbours = "auto";
    std::optional<std::int64_t> particles;
    int width = 1280;
    int height = 720;
    std::string color = "speed";
    std::string camera;
    std::string target;
    std::int64_t maxFrames = 0;  // quit after this many drawn frames; 0: when closed
};

struct Scene;
struct SetupReport;
struct HostParticles;

// Sees what `weir run` writes, e.g. to render it: start() before the simulation is made, then
// every frame.
class RunObserver {
   public:
    virtual ~RunObserver() = default;
    virtual void start(const Scene& scene, const SetupReport& report, const std::string& outDir) = 0;
    virtual void frame(std::int64_t index, double time, const HostParticles& particles) = 0;
};

// A scene file path or a built-in scene's name; empty: the built-in dam break.
Scene resolveScene(const std::string& spec);

int runCommand(const RunOptions& options, RunObserver* observer = nullptr);
int benchCommand(const BenchOptions& options);
int infoCommand();
int validateCommand(const ValidateOptions& options);

}  // namespace weir
