// The Python module weir._weir (re-exported by the weir package, src/python/weir/): exceptions,
// the format tables and build information; scene and simulation bindings in their own files.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <vector>

#include "core/backend.h"
#include "core/check.h"
#include "io/frame_formats.h"
#include "io/io_error.h"
#include "io/mesh_writer.h"
#include "python/bindings.h"
#include "python/scripted_simulation.h"
#include "surface/surface.h"

namespace nb = nanobind;

NB_MODULE(_weir, m) {
    using namespace weir;
    m.doc() = "weir: SPH fluid simulation on the CPU (OpenMP) and NVIDIA GPUs (CUDA).";
    m.attr("__version__") = WEIR_VERSION;

    // Errors as the CLI reports them, by kind; each message names the file, field and value.
    nb::exception<SceneError>(m, "SceneError", PyExc_ValueError).doc() =
        "A scene that cannot be read or run (names the file, the field, the bad value "
        "and what is allowed).";
    nb::exception<IoError>(m, "IoError", PyExc_OSError).doc() =
        "A frame, mesh or index file that cannot be written or read.";
    nb::exception<SimulationError>(m, "SimulationError", PyExc_RuntimeError).doc() =
        "A simulation that cannot be made or run (not enough memory, no CUDA device).";
    nb::exception<SurfaceError>(m, "SurfaceError", PyExc_ValueError).doc() =
        "Particles a surface cannot be built from.";
    nb::exception<BlowUpError>(m, "BlowUpError", PyExc_RuntimeError).doc() =
        "The simulation blew up; the message is the diagnosis (step, time, particle, "
        "likely cause), as weir run prints it.";

    nb::exception<BusyError>(m, "BusyError", PyExc_RuntimeError).doc() =
        "A call on a simulation that another thread is stepping (or reading): one call "
        "at a time on one simulation.";

    m.def("frame_formats", &frameFormatNames,
          "The particle frame formats, as weir run --format names them (the first is the "
          "default).");
    m.def(
        "mesh_formats",
        [] {
            std::vector<std::string> names;
            for (const MeshFormatEntry& entry : meshFormatTable()) {
                names.push_back(entry.name);
            }
            return names;
        },
        "The surface mesh formats, as weir mesh --format names them.");
    m.def("cuda_available", &cudaDeviceAvailable,
          "True when this module has the CUDA backend and a CUDA device is visible.");
    m.def(
        "cuda_built",
        [] {
#if defined(WEIR_HAS_CUDA)
            return true;
#else
            return false;
#endif
        },
        "True when this module was built with the CUDA backend.");

    bindScene(m);
    bindSimulation(m);
}
