// The scene: what the user asks for (geometry, fluid, resolution, timing), as read from JSON.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "scene/mesh_solid.h"

namespace weir {

// A user-facing error in a scene file. The message names the file, the field (as a JSON
// path such as "fluid.restDensity" or "blocks[1].max"), the bad value and what is allowed.
class SceneError : public std::runtime_error {
   public:
    using std::runtime_error::runtime_error;
};

struct Box {
    Vec3d min, max;
};

struct SphereShape {
    Vec3d center;
    double radius = 0;
};

struct FluidBlock {
    Box box;
    Vec3d velocity;
};

struct FluidSphere {
    SphereShape sphere;
    Vec3d velocity;
};

struct MeshIndex;  // scene/boundary.cpp

// A triangle-mesh obstacle read from an OBJ or STL file (ASCII or binary STL), placed by a
// uniform scale then a translation. Triangles in metres after placement; outward normals by the
// right-hand rule (counter-clockwise seen from outside), as both formats specify.
struct MeshObstacle {
    std::string file;  // as written in the scene, resolved against the scene file's folder
    double scale = 1;
    Vec3d translate;
    std::vector<Vec3d> vertices;  // placed
    std::vector<std::array<int, 3>> triangles;
    // The triangles by where they lie across the inside test's ray (scene/boundary.h,
    // buildMeshIndex): built once when the scene is read, shared by copies; null: test them all.
    std::shared_ptr<const MeshIndex> index;
};

enum class Integrator { SemiImplicitEuler, ExplicitEuler };
enum class EquationOfState { Linear, Tait };
enum class WallModel { Simple, Particles };
// "fluid.model": "paper" (Müller et al. 2003 as the paper has it) or "delta-sph" (physics/
// delta_sph.h: Wendland C2, continuity density with density diffusion, Morris viscosity).
enum class FluidModelName { Paper, DeltaSph };

// A container face that moves along itself (its particles stay put: e.g. the top plate of a
// Couette flow, periodic along the motion): "walls.moving": [{"face": "+y", "velocity": [..]}].
struct MovingWall {
    int axis = 0;  // 0, 1, 2 for x, y, z
    int side = 0;  // 0: the face at container.min, 1: at container.max
    Vec3d velocity;
};

// A rigid body (issue 18; physics/rigid_body.h): "bodies": [{"box": {"min", "max"}},
// {"sphere": {"center", "radius"}} or {"mesh": {"file", "scale", "translate"}} (a closed OBJ or STL
// surface), then "density" (kg/m^3) or "mass" (kg) for a floating body,
// or "motion" for a driven one; "velocity" and "angularVelocity" (rad/s) at the start].
enum class BodyDrive { Floating, Oscillate, Rotate };
struct BodySpec {
    bool isSphere = false;
    bool isMesh = false;
    Box box;             // "box"; a mesh's bounds
    SphereShape sphere;  // "sphere"
    MeshObstacle mesh;   // "mesh": placed as an obstacle mesh is
    MeshSolid solid;     // the mesh's volume, centroid and second moment
    double mass = 0;     // kg: "mass", or "density" times the volume; 0 for a driven body
    Vec3d velocity, angularVelocity;
    // "motion": {"oscillate": {"amplitude": [..] m, "period": s, "ramp": s}}: the centre moves by
    // amplitude sin(2 pi t / period), the amplitude ramped up over the first `ramp` seconds; or
    // {"rotate": {"rate": [..] rad/s}}: about the centre at that angular velocity. The centre is
    // the centre of mass (a mesh's centroid).
    BodyDrive drive = BodyDrive::Floating;
    Vec3d amplitude;
    double period = 1, ramp = 0;
    Vec3d rate;
    // The body's bounds at the start.
    Box bounds() const {
        if (!isSphere) {
            return box;
        }
        const Vec3d r(sphere.radius, sphere.radius, sphere.radius);
        return {sphere.center - r, sphere.center + r};
    }
    double volume() const;
    // The centre of mass at the start (of a uniform solid).
    Vec3d centre() const {
        return isSphere ? sphere.center : isMesh ? solid.centroid : (box.min + box.max) * 0.5;
    }
};

// A named fluid: density (kg/m^3) and dynamic viscosity (Pa s) near 20 C.
// An emitter (issue 18; physics/emitter.h): "emitters": [{"disc": {"center", "radius"}} or
// {"rectangle": {"center", "size": [a, b]}}, "direction": [..], "speed": m/s or "rate": m^3/s,
// "start": s, "stop": s]. A rectangle's first size runs along the world x axis projected onto
// its plane (z where the direction is along x), its second across both.
struct EmitterSpec {
    bool isDisc = true;
    Vec3d center;
    double radius = 0;              // a disc's
    double width = 0, height = 0;   // a rectangle's "size"
    Vec3d direction;                // unit
    double speed = 0;               // m/s along the direction ("rate" / area when a rate is given)
    double start = 0, stop = 1e30;  // s
    double area() const;
    // In-plane unit axes: the rectangle's first and second size run along them.
    void planeAxes(Vec3d& u, Vec3d& v) const;
};

struct FluidPreset {
    const char* name;
    double density;
    double viscosity;
    const char* source;
};
// water, oil (olive), honey; nullptr for an unknown name.
const FluidPreset* fluidPreset(const std::string& name);
std::vector<std::string> fluidPresetNames();

struct Scene {
    std::string name = "scene";  // "name", default: file stem
    std::string sourcePath;      // file it came from ("<built-in NAME>" for built-ins)
    std::string description;     // "description", free text, optional
    std::string json;            // the scene as read, compact JSON (a run records it)

    Box container;                             // "container": {"min": [..], "max": [..]}, metres
    std::array<bool, 3> periodic{};            // "container.periodic": [x, y, z] (no walls there)
    std::vector<FluidBlock> blocks;            // "blocks": [{"min","max","velocity"?}]
    std::vector<FluidSphere> spheres;          // "spheres": [{"center","radius","velocity"?}]
    std::vector<Box> obstacleBoxes;            // "obstacles": {"boxes": [{"min","max"}], ...
    std::vector<SphereShape> obstacleSpheres;  //   "spheres": [{"center","radius"}],
    std::vector<MeshObstacle> obstacleMeshes;  //   "meshes": [{"file","scale"?,"translate"?}]}
    std::vector<BodySpec> bodies;              // "bodies": [...] (BodySpec)
    std::vector<EmitterSpec> emitters;         // "emitters": [...] (EmitterSpec)
    std::vector<Box> sinks;                    // "sinks": [{"min", "max"}]: fluid there leaves

    // "fluid": {...}
    std::string preset;  // "preset": "water" | "oil" | "honey" ("" none: water-like)
    FluidModelName model = FluidModelName::Paper;  // "model" (parsed default: "delta-sph")
    std::optional<double> artificialViscosity;     // "artificialViscosity": alpha (delta-sph)
    std::optional<double> densityDiffusion;        // "densityDiffusion": delta (delta-sph)
    std::optional<double> tensileCorrection;       // "tensileCorrection": Monaghan's R (delta-sph;
                                                   // unset: 0.2, 0: off)
    std::optional<double> shifting;                // "shifting": particle shifting's A / Sun et
                                                   // al.'s (delta-sph; unset or 0: off)
    bool eosGiven = false;                         // "eos" was written (else the model's)
    double restDensity = 1000.0;  // "restDensity", kg/m^3, > 0 (default: the preset's)
    std::optional<double>
        viscosity;                 // "viscosity", dynamic mu of eq. 5, Pa s, >= 0; unset: derived
    double physicalViscosity = 0;  // the preset's mu, added to the derived artificial one
    EquationOfState eos = EquationOfState::Linear;  // "eos": "linear" (eq. 3) | "tait"
    // "pressureForce": "symmetric" (Monaghan: tends to grad p) | "paper" (eq. 4: grad p / 2)
    bool paperPressureForce = false;
    // "negativePressureScale" in [0, 1]: share of negative pressure kept (0 clamps, 1 keeps);
    // "clampNegativePressure": true is 0, false is 1.
    double negativePressureScale = 0;
    std::optional<double> stiffness;  // "stiffness", k of eq. 3, m^2/s^2, > 0; unset: derived
    // "clampNegativePressure": eq. 3 gives negative pressure where the free surface lacks
    // neighbours; it pulls surface particles together and throws jets off walls. Clamped by
    // default.
    bool clampNegativePressure = true;

    // "particles": {"spacing": s} or {"count": n} (exactly one; neither: count 20000)
    std::optional<double> spacing;              // metres, > 0
    std::optional<std::int64_t> particleCount;  // > 0
    // "particles.smoothingRatio": h / spacing, in [1.2, 5]; unset: defaultSmoothingRatio
    double smoothingRatio = 2.0;

    Vec3d gravity{0.0, -9.81, 0.0};  // "gravity": [gx, gy, gz], m/s^2

    // "time": {...}
    std::optional<double> timeStep;  // "timeStep", s, > 0; unset: derived (CFL)
    double duration = 2.0;           // "duration", s, > 0
    double frameRate = 30.0;         // "frameRate", frames per simulated second, > 0
    Integrator integrator =
        Integrator::SemiImplicitEuler;  // "integrator":
                                        // "semi-implicit-euler" | "explicit-euler"
    // "adaptive": recompute the step every step from CFL, viscous and force limits (default
    // true, false when timeStep is given).
    std::optional<bool> adaptiveTimeStep;

    // "walls": {...}
    WallModel walls = WallModel::Simple;  // "model": "simple" (the paper) | "particles" (Akinci)
    double wallRestitution = 0.0;  // "restitution", in [0, 1]: normal speed kept after a bounce
    double wallFriction = 0.0;     // "friction", in [0, 1]: tangential speed removed on contact
    bool noSlip = true;            // "slip": "no-slip" | "free-slip" (delta-sph, particles)
    std::vector<MovingWall> movingWalls;  // "moving"

    std::optional<double> maxSpeed;  // "limits.maxSpeed", m/s, > 0; unset: derived
    double maxCompression = 0.5;     // "limits.maxCompression": blow-up past rho0 (1 + this)

    std::string solver;  // "solver": the pressure solver (solver/methods.h); "" the default

    // "dfsph": {...}, the settings of solver "dfsph" (unused by the others). Defaults are
    // SPlisHSPlasH's tolerances.
    struct DfsphSettings {
        double densityErrorPercent = 0.01;    // "densityError": mean |rho - rho0| / rho0, %
        double divergenceErrorPercent = 0.1;  // "divergenceError": mean dt |Drho/Dt| / rho0, %;
                                              // 0: no divergence-free solve
        double worstDensityErrorPercent = 1;  // "worstDensityError": the constant-density solve
                                              // also sweeps while one particle's error is past
                                              // it, %; 0: the mean alone
        int maxSweeps = 100;                  // "maxSweeps": the most Jacobi sweeps of a solve
        double cfl = 0.4;                     // "cfl": dt <= cfl d / max |v|
    } dfsph;
};

// The smoothing ratio h / d (h the kernel's support) of a scene that does not give
// particles.smoothingRatio. 3 for the delta-SPH model under WCSPH: Wendland C2 over 2 d has about
// 33 neighbours, too few for small waves (a piston's 26 mm wave lost 80% of its height within
// 1 m at 2 d, none at 3 d; measured on an H200, docs/physics.md). 2 for the paper's model (its
// kernels at its h, so Tables 1-3 stay the paper's) and for DFSPH (its Jacobi sweeps blew up at
// 3 d in the stability sweep, docs/dfsph.md).
double defaultSmoothingRatio(FluidModelName model, const std::string& solver);

// Reads and validates a scene file; throws SceneError naming file, field, value, allowed range.
Scene loadScene(const std::string& path);
// Same for JSON text already in memory; sourceName is used in messages.
Scene parseScene(const std::string& jsonText, const std::string& sourceName);
// The built-in scenes (scenes/*.json, embedded), by name ("dam_break", ...). An unknown name
// throws SceneError listing them, with a did-you-mean.
Scene builtinScene(const std::string& name);
std::vector<std::string> builtinSceneNames();
// The same scene read again with fluid.model set to `model` ("paper" or "delta-sph"), so that
// every default that follows the model (equation of state, walls, pressure clamp) follows it
// too; throws SceneError as parseScene does (e.g. delta-sph fields asked of the paper's model).
Scene withFluidModel(const Scene& scene, const std::string& model);
// The scene with its "solver" replaced (a registered pressure solver, solver/methods.h).
Scene withSolver(const Scene& scene, const std::string& solver);
// The scene with `patchJson` (a JSON object of scene fields) merged into it as a JSON merge patch
// (RFC 7396: objects merge field by field, anything else replaces, null removes), then read
// again; throws SceneError as parseScene does, naming the field a bad override gives.
Scene withOverrides(const Scene& scene, const std::string& patchJson);
// A scene file path or a built-in scene's name, as `weir run SCENE` takes it; empty: the built-in
// dam break. Throws SceneError naming the file, or listing the built-in scenes with a
// did-you-mean.
Scene resolveScene(const std::string& spec);
// " (did you mean 'dam_break'?)" for a name close to a built-in scene's ("dambreak"), else "".
std::string didYouMeanBuiltinScene(const std::string& name);

}  // namespace weir
