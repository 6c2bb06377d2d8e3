// The weir subcommands, each a function from parsed options to an exit code.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace weir {

class Communicator;  // cluster/communicator.h

// Exit codes shared by all commands.
constexpr int kExitOk = 0;
constexpr int kExitError = 1;             // bad scene, I/O failure, not enough memory
constexpr int kExitUsage = 2;             // bad command-line arguments
constexpr int kExitBlowUp = 3;            // the simulation blew up; frames already written stay
constexpr int kExitValidationFailed = 4;  // weir validate: a check missed its tolerance

// Inside a catch block: the exception being handled, as a message and the exit code it means
// (kExitUsage for bad input, std::invalid_argument; kExitError for anything else).
struct CaughtError {
    std::string what;
    int exitCode;
};
CaughtError caughtError();
// Inside a catch block: prints "PREFIX: error: WHAT" and returns caughtError()'s exit code.
int reportCaughtError(const std::string& prefix = "weir");
// The same for a rank of a distributed run: names the rank and, with other ranks, ends them all.
int reportCaughtError(Communicator& comm);

struct RunOptions {
    std::string scene;   // file path or built-in name; empty: the built-in dam break
    std::string model;   // fluid.model to run the scene with; "" the scene's own
    std::string solver;  // the pressure solver to run it with; "" the scene's own
    std::string backend = "auto";
    std::string neighbours = "auto";
    std::optional<std::int64_t> particles;
    std::optional<std::int64_t> frames;
    std::string outDir;  // empty: out/<scene name>
    std::string format = "vtu";
    // The number of the first frame (the initial state) in file names and frames.json; 1 for
    // tools that count from 1 (Houdini's $F). Frame k of the run is numbered first + k.
    std::int64_t firstFrameNumber = 0;
    double cellSize = 0;  // the vdb format's voxel [m]; 0: half the particle spacing
    bool explain = false;
    bool quiet = false;
    bool render = false;     // also render each frame to <out>/images/ (weir_render)
    bool mesh = false;       // also write each frame's surface to <out>/mesh/
    bool usd = false;        // also write <out>/frames.usda after the last frame
    bool overwrite = false;  // replace the frames of an earlier run in outDir
};

struct BenchOptions {
    std::string scene;              // file or built-in name; empty: dam break
    std::string model = "paper";    // fluid.model timed: the paper's, whatever the scene says
    std::string solver;             // pressure solver timed; "" the scene's
    std::string sizes = "10k,50k";  // particle counts, k/M suffixes allowed
    std::string columns = "auto";   // cpu-brute,cpu-grid,...,cuda-dense or auto
    int steps = 20;                 // timed steps (median per stage)
    int warmup = 3;                 // untimed steps before timing
    double settle = 0.1;            // simulated seconds before timing: a fluid in motion
    double budget = 60;             // seconds per (size, column); longer runs are skipped
    std::string outDir = "bench-out";
    bool noPlot = false;
    bool noRender = false;  // skip the point-sprite rendering row
    bool scaling = false;   // weak and strong scaling of distributed runs (under mpirun)
};

struct ValidateOptions {
    std::string backend = "auto";
    std::string model;   // fluid.model of every case; "" the scenes' default
    std::string solver;  // pressure solver of every case; "" the scenes' default
    std::string cases = "hydrostatic,dam-break";  // of hydrostatic, dam-break, viscous, channels,
                                                  // lobovsky, taylor-green
    int channelResolution = 20;                   // particles across the channel
    int lobovskyResolution = 20;                  // particles over the Lobovsky column's height
    std::vector<int> taylorGreenResolutions{32};  // particles across the Taylor-Green box
    double shifting = -1;        // fluid.shifting of every case (delta-sph); < 0: the default
    double smoothingRatio = -1;  // particles.smoothingRatio of every case; < 0: the default
    int tankResolution = 24;     // particles over the tank's water depth
    std::vector<int> columnResolutions{12};  // particles across the dam-break column (a ladder)
    double damEndT = 5.0;                    // dimensionless end time T = t sqrt(2 g / a)
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
    std::string camera;    // "yaw,pitch,distance"; empty: framed on the container
    std::string target;    // "x,y,z"; empty: the container's centre
    std::string scene;     // scene whose container and obstacles are drawn; empty: the run's own
                           // (recorded in frames.json), else none
    std::string video;     // an .mp4 made from the images with ffmpeg; empty: none
    bool surface = false;  // draw the marching-cubes surface instead of particles
    std::string backend = "auto";            // where the surface is reconstructed
    std::string surfaceField = "isotropic";  // isotropic or anisotropic (surface/surface.h)
    double spacing = 0;            // particle spacing [m]; 0: from the scene or the first frame
    std::string look = "preview";  // preview (OpenGL) or water (path traced, raytrace/)
    int samples = 0;  // per pixel: multisampling (preview) or paths (water); 0: the look's default
    std::string exportWater;  // --look water: also write what is traced here; empty: nothing
    // --look water: the shutter is open for this share of the time between frames, centred on
    // the frame, the surface moved by its velocity (0: no motion blur).
    double motionBlur = 0;
    // Spray, foam and bubbles (whitewater_NNNNN.ply, `weir whitewater`) drawn with the fluid from
    // this folder; empty: FRAMES/whitewater where it exists. noWhitewater: none.
    std::string whitewater;
    bool noWhitewater = false;
    bool quiet = false;
    std::optional<std::int64_t> frame;  // --frame N: only this frame
    std::string frames;                 // --frames A:B: frames A to B (cli/frame_selection.h)
};

// `weir mesh` and `weir run --mesh`: the fluid surface of each frame by marching cubes.
struct MeshOptions {
    std::string framesDir;
    std::string outDir;               // empty: <framesDir>/mesh
    std::string formats = "obj,ply";  // one or both
    std::string backend = "auto";
    double spacing = 0;   // particle spacing [m]; 0: estimated from the first frame (or the run)
    double cellSize = 0;  // marching-cubes cell [m]; 0: half the spacing
    double iso = 0;       // in particle spacings; > 0 inflates
    std::string surfaceField = "isotropic";  // isotropic or anisotropic (surface/surface.h)
    bool quiet = false;
    std::optional<std::int64_t> frame;  // --frame N: only this frame
    std::string frames;                 // --frames A:B: frames A to B
};

// `weir usd` and `weir run --usd`: a run's frames (and surface meshes) as one USD stage.
struct UsdOptions {
    std::string framesDir;
    std::string outPath;  // empty: <framesDir>/frames.usda
    std::string meshDir;  // surface_NNNNN.ply/.obj; empty: <framesDir>/mesh
    bool noMeshes = false;
    std::string scene;   // container and obstacles; empty: the run's own (frames.json)
    double spacing = 0;  // particle spacing [m]; 0: the run's, else measured on the first frame
    std::optional<std::int64_t> frame;  // --frame N: only this frame
    std::string frames;                 // --frames A:B: frames A to B
};

// `weir whitewater` and `weir run --whitewater`: spray, foam and bubbles (src/whitewater/).
struct WhitewaterOptions {
    std::string framesDir;
    std::string outDir;  // empty: <framesDir>/whitewater
    std::string frames;  // --frames A:B: frames A to B (the first starts with none)
    std::int64_t maxParticles = 2'000'000;
    double rate = 100;     // diffuse particles per fluid particle per second at full potential
    double lifetime = 2;   // foam's mean lifetime [s]
    int substeps = 0;      // per frame interval; 0: automatic
    bool explain = false;  // print the scale, the thresholds and the potentials of the first frame
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
    std::string press;           // keys pressed on successive frames, e.g. "none,c,m,space"
    std::string screenshot;      // PNG of the last frame (with maxFrames)
    std::string record;          // an .mp4 of every frame drawn, made by ffmpeg; empty: none
};

struct Scene;
struct SetupReport;
struct HostParticles;

// Sees what `weir run` writes, e.g. to render it: start() before the simulation is made, then
// every frame.
class RunObserver {
   public:
    virtual ~RunObserver() = default;
    virtual void start(const Scene& scene, const SetupReport& report,
                       const std::string& outDir) = 0;
    virtual void frame(std::int64_t index, double time, const HostParticles& particles) = 0;
    // After the last frame of a run that did not fail: a summary line.
    virtual void finish() {}
};

// Several observers as one, called in order.
class RunObserverList : public RunObserver {
   public:
    void add(std::unique_ptr<RunObserver> observer) { list_.push_back(std::move(observer)); }
    bool empty() const { return list_.empty(); }
    void start(const Scene& scene, const SetupReport& report, const std::string& outDir) override {
        for (auto& o : list_) o->start(scene, report, outDir);
    }
    void frame(std::int64_t index, double time, const HostParticles& particles) override {
        for (auto& o : list_) o->frame(index, time, particles);
    }
    void finish() override {
        for (auto& o : list_) o->finish();
    }

   private:
    std::vector<std::unique_ptr<RunObserver>> list_;
};

int runCommand(const RunOptions& options, RunObserver* observer = nullptr);
int meshCommand(const MeshOptions& options);
// `weir run --mesh`: writes <out>/mesh/surface_NNNNN.{obj,ply} for every frame. Throws
// std::invalid_argument for bad options.
std::unique_ptr<RunObserver> makeRunMesher(const MeshOptions& options);
int whitewaterCommand(const WhitewaterOptions& options);
// `weir run --whitewater`: <out>/whitewater/whitewater_NNNNN.ply for every frame. Throws
// std::invalid_argument for bad options.
std::unique_ptr<RunObserver> makeRunWhitewater(const WhitewaterOptions& options);
int usdCommand(const UsdOptions& options);
// `weir run --usd`: after the run's last frame, <out>/frames.usda (or options.outPath).
std::unique_ptr<RunObserver> makeRunUsdWriter(const UsdOptions& options);
// Times drawing particles as point sprites, for weir bench's rendering row (paper Tables 1-3);
// made by src/render/ where rendering is built.
class SpriteDrawTimer {
   public:
    virtual ~SpriteDrawTimer() = default;
    // Median ms to upload the particles and draw them as shaded sprites into a 1280 x 720
    // offscreen image, waiting for the GPU (no read-back).
    virtual double medianDrawMs(const Scene& scene, const HostParticles& particles,
                                double radius) = 0;
    virtual std::string description() const = 0;
};

int benchCommand(const BenchOptions& options, SpriteDrawTimer* spriteTimer = nullptr);
// `weir bench --scaling` (cli/scaling_bench.cpp).
int scalingBenchCommand(const BenchOptions& options);
// "a,b,,c" as {"a", "b", "c"}.
std::vector<std::string> splitList(const std::string& text);
// renderingBuilt: whether this binary has the drawing commands (known where they are linked).
int infoCommand(bool renderingBuilt);
int validateCommand(const ValidateOptions& options);

}  // namespace weir
