// weir.Simulation: stepping with the GIL released, the particles as NumPy arrays (original
// order) or zero-copy DLPack views (cell order, on the GPU for a CUDA run), frames, meshes,
// explain() and a per-frame callback. weir.FrameWriter and weir.Mesh write what the CLI writes.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/filesystem.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/backend.h"
#include "io/frame_formats.h"
#include "io/frame_writer.h"
#include "io/mesh_writer.h"
#include "python/bindings.h"
#include "python/scripted_simulation.h"

namespace nb = nanobind;

namespace weir {

namespace {

// A NumPy array that owns `data` (moved to the heap, freed with the array).
template <class T>
nb::ndarray<nb::numpy, T> ownedArray(std::vector<T>&& data,
                                     std::initializer_list<std::size_t> shape) {
    auto* heap = new std::vector<T>(std::move(data));
    nb::capsule owner(heap, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
    return nb::ndarray<nb::numpy, T>(heap->data(), shape, owner);
}

// The columns a, b, c as one (n, 3) array.
nb::ndarray<nb::numpy, Real> interleave(const std::vector<Real>& a, const std::vector<Real>& b,
                                        const std::vector<Real>& c) {
    const std::size_t n = a.size();
    std::vector<Real> out(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        out[3 * i] = a[i];
        out[3 * i + 1] = b[i];
        out[3 * i + 2] = c[i];
    }
    return ownedArray(std::move(out), {n, 3});
}

nb::ndarray<nb::numpy, Real> column(const std::vector<Real>& a) {
    return ownedArray(std::vector<Real>(a), {a.size()});
}

nb::ndarray<nb::numpy, std::int32_t> originalIds(std::size_t n) {
    std::vector<std::int32_t> ids(n);
    for (std::size_t i = 0; i < n; ++i) {
        ids[i] = std::int32_t(i);
    }
    return ownedArray(std::move(ids), {n});
}

nb::ndarray<nb::numpy, float> vectors(const std::vector<Vec3f>& v) {
    std::vector<float> out(3 * v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        out[3 * i] = v[i].x;
        out[3 * i + 1] = v[i].y;
        out[3 * i + 2] = v[i].z;
    }
    return ownedArray(std::move(out), {v.size(), 3});
}

// The particle arrays where the simulation keeps them, as DLPack-capable views that keep the
// simulation alive: positions (x, y, z, mark) and velocities (vx, vy, vz, density) as (n, 4),
// ids as (n,), in cell order.
struct ParticleViews {
    nb::object positions, velocities, ids;
    std::int64_t count = 0;
    bool onDevice = false;
    int deviceId = 0;
};

ParticleViews particleViews(ScriptedSimulation& sim, nb::handle owner) {
    const ParticleArrays a = sim.deviceArrays();
    ParticleViews v;
    v.count = a.count;
    v.onDevice = a.onDevice;
    v.deviceId = a.onDevice ? currentCudaDevice() : 0;
    const int device = a.onDevice ? nb::device::cuda::value : nb::device::cpu::value;
    const std::size_t n = std::size_t(a.count);
    auto view = [&](const void* data, std::initializer_list<std::size_t> shape,
                    nb::dlpack::dtype dtype) {
        // Writable: a consumer may change the state between steps (in cell order).
        return nb::cast(nb::ndarray<nb::array_api>(const_cast<void*>(data), shape, owner, {}, dtype,
                                                   device, v.deviceId));
    };
    v.positions = view(a.pos, {n, 4}, nb::dtype<Real>());
    v.velocities = view(a.vel, {n, 4}, nb::dtype<Real>());
    v.ids = view(a.id, {n}, nb::dtype<Index>());
    return v;
}

struct Mesh {
    TriangleMesh mesh;
};

MeshFormat meshFormatFor(const std::string& path, const std::optional<std::string>& format) {
    if (format) {
        return parseMeshFormat(*format);
    }
    std::string extension = std::filesystem::path(path).extension().string();
    if (!extension.empty()) {
        extension.erase(0, 1);
    }
    try {
        return parseMeshFormat(extension);
    } catch (const std::invalid_argument&) {
        throw std::invalid_argument("mesh file '" + path + "': the extension '" + extension +
                                    "' names no mesh format; allowed are " + meshFormatList() +
                                    " (or give format=)");
    }
}

// surface_00012.obj, as weir mesh and weir run --mesh name them.
std::string meshFileName(std::int64_t index, MeshFormat format) {
    char name[40];
    std::snprintf(name, sizeof name, "surface_%05lld.%s", static_cast<long long>(index),
                  meshExtension(format).c_str());
    return name;
}

SurfaceOptions surfaceOptions(std::optional<double> spacing, double cellSize, double iso,
                              const std::string& field = "isotropic") {
    SurfaceOptions options;
    options.field = parseSurfaceField(field);
    options.spacing = spacing.value_or(0);
    options.cellSize = cellSize;
    options.iso = iso;
    return options;
}

Backend surfaceBackend(ScriptedSimulation& sim, const std::optional<std::string>& backend) {
    return backend ? parseBackend(*backend) : sim.simulation().backend();
}

nb::dict explain(ScriptedSimulation& sim) {
    const SetupReport& r = sim.report();
    const SphParams& p = sim.simulation().params();
    nb::dict d;
    d["scene"] = sim.scene().name;
    d["model"] = p.model == FluidModel::DeltaSph ? "delta-sph" : "paper";
    d["solver"] = sim.simulation().method();
    d["backend"] = backendName(sim.simulation().backend());
    d["neighbours"] = neighbourModeName(sim.neighbourMode());
    d["particles"] = std::int64_t(sim.simulation().particleCount());
    d["spacing"] = r.spacing;
    d["smoothing_radius"] = r.smoothingRadius;
    d["fluid_volume"] = r.fluidVolume;
    d["fluid_height"] = r.fluidHeight;
    d["expected_speed"] = r.expectedSpeed;
    d["speed_of_sound"] = r.speedOfSound;
    d["lattice_kernel_sum"] = r.latticeKernelSum;
    d["gradient_moment"] = r.gradientMoment;
    d["steps_per_frame"] = r.stepsPerFrame;
    d["frame_interval"] = r.frameInterval;
    d["frames"] = r.frames;
    d["mass"] = double(p.mass);
    d["rest_density"] = double(p.restDensity);
    d["stiffness"] = double(p.stiffness);
    d["viscosity"] = double(p.viscosity);
    d["dynamic_viscosity"] = double(p.dynamicViscosity);
    d["artificial_viscosity"] = double(p.artificialViscosity);
    d["density_diffusion"] = double(p.densityDiffusion);
    d["shifting"] = double(p.shifting);
    d["time_step"] = double(p.timeStep);
    d["adaptive_time_step"] = p.adaptiveTimeStep;
    d["max_speed"] = double(p.maxSpeed);
    d["gravity"] = nb::make_tuple(double(p.gravity.x), double(p.gravity.y), double(p.gravity.z));
    d["lines"] = r.lines;
    d["warnings"] = r.warnings;
    return d;
}

void run(nb::handle self, std::optional<std::int64_t> frames, nb::handle onFrame,
         std::optional<std::filesystem::path> out, const std::string& format,
         const std::vector<std::string>& meshFormats) {
    ScriptedSimulation& sim = nb::cast<ScriptedSimulation&>(self);
    const double interval = sim.report().frameInterval;
    if (frames && *frames < 0) {
        throw std::invalid_argument("run(frames=" + std::to_string(*frames) +
                                    "): give frames >= 0, or None for the scene's duration");
    }
    std::unique_ptr<FrameWriter> writer;
    if (out) {
        writer = std::make_unique<FrameWriter>(out->string(), parseFrameFormat(format));
        writer->setScale(sim.report().spacing, 0);  // vdb frames: the run's spacing, voxel d / 2
    }
    std::vector<MeshFormat> meshes;
    for (const std::string& name : meshFormats) {
        meshes.push_back(parseMeshFormat(name));
    }
    if (!meshes.empty() && !out) {
        throw std::invalid_argument("run(mesh=...) writes into out/mesh/: give out= as well");
    }
    const std::string meshDir = out ? (*out / "mesh").string() : "";
    if (!meshes.empty()) {
        std::filesystem::create_directories(meshDir);
    }
    // Frames are at whole multiples of the frame interval, as weir run's; the current state is
    // the first frame when it lies on one.
    const double now = sim.simulation().time();
    std::int64_t first = std::int64_t(std::ceil(now / interval - 1e-6));
    const std::int64_t last = frames ? first + *frames : sim.report().frames;
    for (std::int64_t k = first; k <= last; ++k) {
        const double time = double(k) * interval;
        if (time > sim.simulation().time()) {
            nb::gil_scoped_release release;
            sim.advanceTo(time);
        }
        if (writer) {
            sim.writeFrame(*writer, int(k));
        }
        if (!meshes.empty()) {
            TriangleMesh mesh;
            {
                nb::gil_scoped_release release;
                mesh = sim.surface(sim.simulation().backend(), SurfaceOptions{});
            }
            // The frame beside the mesh, for vdb surfaces (level set, velocity and points).
            const SurfaceFrame frame{mesh, &sim.particles(), sim.report().spacing,
                                     sim.report().spacing / 2, time};
            for (MeshFormat f : meshes) {
                writeMesh((std::filesystem::path(meshDir) / meshFileName(k, f)).string(), f, frame);
            }
        }
        if (onFrame.is_valid() && !onFrame.is_none()) {
            onFrame(self, k, time);
        }
        if (PyErr_CheckSignals() != 0) {  // Ctrl-C between frames
            throw nb::python_error();
        }
    }
}

}  // namespace

void bindSimulation(nb::module_& m) {
    nb::class_<ParticleViews>(
        m, "ParticleArrays",
        "The particle arrays where the simulation keeps them (GPU memory for a CUDA run), without "
        "a copy, in the current cell order (ids says which particle each row is). Each array "
        "supports DLPack (__dlpack__, __dlpack_device__): cupy.from_dlpack, torch.from_dlpack, "
        "jax.dlpack.from_dlpack and numpy.from_dlpack (CPU) take it without copying. Valid "
        "until the next step; they keep the simulation alive.")
        .def_ro("positions", &ParticleViews::positions,
                "(n, 4) x, y, z [m] and a marker, float32 (float64 in a double build).")
        .def_ro("velocities", &ParticleViews::velocities,
                "(n, 4) vx, vy, vz [m/s] and density [kg/m^3].")
        .def_ro("ids", &ParticleViews::ids,
                "(n,) int32: each row's particle id (its index in "
                "the initial, original order).")
        .def_ro("count", &ParticleViews::count, "Particles n.")
        .def_ro("on_device", &ParticleViews::onDevice, "True for CUDA device memory.")
        .def_ro("device_id", &ParticleViews::deviceId, "The CUDA device ordinal (0 on the CPU).");

    nb::class_<Mesh>(m, "Mesh",
                     "A triangle mesh of the fluid's surface (marching cubes), as weir mesh "
                     "writes it.")
        .def_prop_ro(
            "vertices", [](const Mesh& m) { return vectors(m.mesh.positions); },
            nb::rv_policy::move, "(V, 3) float32 vertex positions [m].")
        .def_prop_ro(
            "normals", [](const Mesh& m) { return vectors(m.mesh.normals); }, nb::rv_policy::move,
            "(V, 3) float32 unit normals, out of the fluid.")
        .def_prop_ro(
            "triangles",
            [](const Mesh& m) {
                std::vector<std::uint32_t> copy(m.mesh.indices);
                return ownedArray(std::move(copy), {m.mesh.triangleCount(), 3});
            },
            nb::rv_policy::move,
            "(T, 3) uint32 vertex indices, counter-clockwise seen from outside.")
        .def_prop_ro(
            "vertex_count", [](const Mesh& m) { return m.mesh.vertexCount(); }, "V.")
        .def_prop_ro(
            "triangle_count", [](const Mesh& m) { return m.mesh.triangleCount(); }, "T.")
        .def(
            "write",
            [](const Mesh& m, const std::filesystem::path& path,
               std::optional<std::string> format) {
                writeMesh(path.string(), meshFormatFor(path.string(), format), m.mesh);
            },
            nb::arg("path"), nb::arg("format") = nb::none(),
            "Writes the mesh atomically; the format ('obj' or 'ply', weir.mesh_formats()) "
            "from the file's extension unless given. Raises IoError.");

    nb::class_<FrameWriter>(m, "FrameWriter",
                            "Writes numbered particle frames (<dir>/frame_00000.vtu, ...) in one "
                            "format with frames.json, and frame.pvd for vtu, as weir run does: "
                            "weir render and weir mesh read the folder.")
        .def(
            "__init__",
            [](FrameWriter* self, const std::filesystem::path& directory, const std::string& format,
               const std::string& baseName) {
                new (self) FrameWriter(directory.string(), parseFrameFormat(format), baseName);
            },
            nb::arg("directory"), nb::arg("format") = "vtu", nb::arg("base_name") = "frame",
            "Creates the folder and its parents (IoError if impossible); format: "
            "weir.frame_formats().")
        .def(
            "write",
            [](FrameWriter& w, ScriptedSimulation& sim, int index) { sim.writeFrame(w, index); },
            nb::arg("simulation"), nb::arg("index"),
            "Writes the simulation's current state as frame `index` (at its current time), "
            "atomically; writing an index again replaces it. Raises IoError.")
        .def("path", &FrameWriter::framePath, nb::arg("index"), "The file of frame `index`.")
        .def_prop_ro("directory", &FrameWriter::dir)
        .def_prop_ro("format", [](const FrameWriter& w) { return std::string(w.format().name()); })
        .def_prop_ro("index_path", &FrameWriter::indexPath, "<directory>/frames.json.");

    nb::class_<ScriptedSimulation>(
        m, "Simulation",
        "A simulation of a scene, set up as weir run sets it up (the same derived parameters, "
        "checks and errors). Stepping releases the GIL; a blow-up raises BlowUpError with the "
        "diagnosis. One call at a time: a call from another thread while one steps raises "
        "BusyError.")
        .def(
            "__init__",
            [](ScriptedSimulation* self, nb::handle scene, const std::string& backend,
               std::optional<std::string> solver, std::optional<std::string> model,
               std::optional<std::int64_t> particles, const std::string& neighbours,
               nb::handle overrides) {
                Scene s = sceneFrom(scene);
                if (overrides.is_valid() && !overrides.is_none()) {
                    s = withOverrides(
                        s, nb::isinstance<nb::str>(overrides)
                               ? nb::cast<std::string>(overrides)
                               : nb::cast<std::string>(
                                     nb::module_::import_("json").attr("dumps")(overrides)));
                }
                ScriptedOptions o;
                o.backend = backend;
                o.solver = solver.value_or("");
                o.model = model.value_or("");
                o.particles = particles;
                o.neighbours = neighbours;
                nb::gil_scoped_release release;
                new (self) ScriptedSimulation(s, o);
            },
            nb::arg("scene"), nb::kw_only(), nb::arg("backend") = "auto",
            nb::arg("solver") = nb::none(), nb::arg("model") = nb::none(),
            nb::arg("particles") = nb::none(), nb::arg("neighbours") = "auto",
            nb::arg("overrides") = nb::none(),
            nb::sig("def __init__(self, scene: Scene | str | os.PathLike[str] | "
                    "dict[str, typing.Any], *, backend: str = 'auto', solver: str | None = None, "
                    "model: str | None = None, particles: int | None = None, "
                    "neighbours: str = 'auto', overrides: dict[str, typing.Any] | str | None = "
                    "None) -> None"),
            "scene: a Scene, a file path or built-in name, or a dict (weir.load_scene). "
            "backend: 'auto' (the GPU when one is visible), 'cpu' or 'cuda'. solver: 'wcsph' or "
            "'dfsph' (None: the scene's). model: 'delta-sph' or 'paper' (None: the scene's). "
            "particles: about this many particles (None: the scene's resolution). neighbours: "
            "'auto', 'dense', 'grid' or 'brute'. overrides: a dict of scene fields merged into "
            "the scene (Scene.with_overrides). Raises SceneError, SimulationError or ValueError "
            "as weir run reports them.")
        .def("step", &ScriptedSimulation::step, nb::arg("n") = 1,
             nb::call_guard<nb::gil_scoped_release>(),
             "Advances n time steps in one call into the engine (no copies), then reads the "
             "fault record once (raises BlowUpError). Releases the GIL.")
        .def("advance_to", &ScriptedSimulation::advanceTo, nb::arg("time"),
             nb::call_guard<nb::gil_scoped_release>(),
             "Advances until the simulated time is `time` seconds (the last step cut to land "
             "on it), as weir run does between frames. Raises BlowUpError. Releases the GIL.")
        .def("run", &run, nb::arg("frames") = nb::none(), nb::arg("on_frame") = nb::none(),
             nb::arg("out") = nb::none(), nb::arg("format") = "vtu",
             nb::arg("mesh") = std::vector<std::string>{},
             nb::sig("def run(self, frames: int | None = None, on_frame: "
                     "collections.abc.Callable[[Simulation, int, float], object] | None = None, "
                     "out: str | os.PathLike[str] | None = None, format: str = 'vtu', "
                     "mesh: collections.abc.Sequence[str] = []) -> None"),
             "Runs frame by frame, as weir run: frames lie at multiples of the scene's frame "
             "interval; the current state is the first when it lies on one. frames: how many "
             "after the first (None: to the scene's duration). on_frame(sim, index, time) is "
             "called after each frame. out: a folder to write frames to (format: "
             "weir.frame_formats()), mesh: mesh formats to write each frame's surface in, to "
             "out/mesh/surface_NNNNN.EXT. Raises BlowUpError (frames already written are kept).")
        .def(
            "positions",
            [](ScriptedSimulation& s) {
                const HostParticles& h = s.particles();
                return interleave(h.x, h.y, h.z);
            },
            "(n, 3) positions [m] in the original particle order (row i is particle id i); a "
            "copy. The particles are downloaded once per state, whichever array asks first.")
        .def(
            "velocities",
            [](ScriptedSimulation& s) {
                const HostParticles& h = s.particles();
                return interleave(h.vx, h.vy, h.vz);
            },
            "(n, 3) velocities [m/s], original order; a copy.")
        .def(
            "density", [](ScriptedSimulation& s) { return column(s.particles().rho); },
            "(n,) density [kg/m^3], original order; a copy.")
        .def(
            "pressure", [](ScriptedSimulation& s) { return column(s.particles().p); },
            "(n,) pressure [Pa] from the density by the equation of state, original order; a "
            "copy (as frames hold it).")
        .def(
            "ids",
            [](ScriptedSimulation& s) {
                const HostParticles& p = s.particles();
                if (p.id.empty()) {
                    return originalIds(p.size());
                }
                std::vector<std::int32_t> ids(p.id.begin(), p.id.end());
                return ownedArray(std::move(ids), {p.size()});
            },
            "(n,) int32 ids of the rows of the other arrays: 0 .. n - 1, as they are in the "
            "original order; with emitters or sinks, the live particles' ids in increasing order "
            "(an emitted particle gets a fresh id; ids are never reused).")
        .def(
            "particle_arrays",
            [](nb::handle self) {
                ScriptedSimulation& s = nb::cast<ScriptedSimulation&>(self);
                return particleViews(s, self);
            },
            "The arrays where they live, without a copy (ParticleArrays: DLPack views, on the "
            "GPU for a CUDA run), in cell order; waits for queued GPU work first.")
        .def(
            "surface",
            [](ScriptedSimulation& s, std::optional<std::string> backend,
               std::optional<double> spacing, double cellSize, double iso,
               const std::string& field) {
                const Backend b = surfaceBackend(s, backend);
                const SurfaceOptions options = surfaceOptions(spacing, cellSize, iso, field);
                nb::gil_scoped_release release;
                return Mesh{s.surface(b, options)};
            },
            nb::arg("backend") = nb::none(), nb::arg("spacing") = nb::none(),
            nb::arg("cell_size") = 0.0, nb::arg("iso") = 0.0, nb::arg("field") = "isotropic",
            "The fluid's surface now, by marching cubes (as weir mesh): spacing None takes the "
            "run's particle spacing, cell_size 0 half of it, iso in particle spacings (> 0 "
            "inflates), field 'isotropic' or 'anisotropic' (weir mesh --surface-field); backend "
            "None: the simulation's.")
        .def(
            "write_frame",
            [](ScriptedSimulation& s, const std::filesystem::path& file,
               std::optional<std::string> format) {
                const std::string path = file.string();
                const std::string ext = file.extension().string();
                const FrameFormat f =
                    parseFrameFormat(format ? *format : (ext.empty() ? ext : ext.substr(1)));
                f.entry().write(path, s.particles(), FrameInfo{s.simulation().time()});
            },
            nb::arg("path"), nb::arg("format") = nb::none(),
            "Writes the current state to one frame file (format from the extension unless "
            "given: weir.frame_formats()); FrameWriter writes numbered series.")
        .def("explain", &explain,
             "The derived parameters (what weir run --explain prints) as a dict: spacing, "
             "smoothing_radius, speed_of_sound, time_step, stiffness, viscosity, mass, "
             "steps_per_frame, frames, ... and 'lines', the explanation, one per decision, and "
             "'warnings'.")
        .def_prop_ro(
            "fault",
            [](ScriptedSimulation& s) -> std::optional<std::string> {
                std::string text = s.faultText();
                return text.empty() ? std::nullopt : std::optional<std::string>(text);
            },
            "The first fault's diagnosis, or None.")
        .def_prop_ro(
            "time", [](ScriptedSimulation& s) { return s.simulation().time(); },
            "Simulated time, s.")
        .def_prop_ro(
            "step_count", [](ScriptedSimulation& s) { return s.simulation().stepCount(); },
            "Steps taken.")
        .def_prop_ro(
            "particle_count",
            [](ScriptedSimulation& s) { return std::int64_t(s.simulation().particleCount()); })
        .def_prop_ro(
            "backend",
            [](ScriptedSimulation& s) {
                return std::string(backendName(s.simulation().backend()));
            },
            "'cpu' or 'cuda'.")
        .def_prop_ro("device_name",
                     [](ScriptedSimulation& s) { return s.simulation().deviceName(); })
        .def_prop_ro(
            "solver", [](ScriptedSimulation& s) { return s.simulation().method(); },
            "The pressure solver: 'wcsph' or 'dfsph'.")
        .def_prop_ro(
            "neighbours",
            [](ScriptedSimulation& s) { return std::string(neighbourModeName(s.neighbourMode())); })
        .def_prop_ro(
            "scene", [](ScriptedSimulation& s) { return s.scene(); },
            "The scene as run (with the solver, model and overrides applied).")
        .def_prop_ro(
            "spacing", [](ScriptedSimulation& s) { return s.report().spacing; },
            "Particle spacing d, m.")
        .def_prop_ro(
            "frame_interval", [](ScriptedSimulation& s) { return s.report().frameInterval; },
            "Simulated seconds between frames, s.")
        .def_prop_ro(
            "frame_count", [](ScriptedSimulation& s) { return s.report().frames; },
            "Frames of the scene's duration after frame 0.")
        .def("__repr__", [](ScriptedSimulation& s) {
            return "weir.Simulation('" + s.scene().name + "', " +
                   std::to_string(s.simulation().particleCount()) + " particles, " +
                   backendName(s.simulation().backend()) +
                   ", t = " + std::to_string(s.simulation().time()) + " s)";
        });
}

}  // namespace weir
