"""weir: SPH fluid simulation on the CPU (OpenMP) and NVIDIA GPUs (CUDA), from Python.

    import weir
    sim = weir.Simulation("dam_break", backend="cpu", particles=20_000)
    sim.advance_to(0.5)
    x = sim.positions()          # (n, 3) NumPy array, original particle order

The same engine as the ``weir`` command line: scenes, derived parameters, errors and file
formats are the CLI's. See docs/python.md.
"""

import os as _os

# OpenMP threads sleep while they wait unless the user chose otherwise (as the weir binary does):
# spinning threads made a small run 13x slower on a machine with one other busy process. libgomp
# reads this once, as it loads, so it is set before the extension module loads it.
_os.environ.setdefault("OMP_WAIT_POLICY", "passive")

from ._weir import (  # noqa: E402
    BlowUpError,
    BusyError,
    FrameWriter,
    IoError,
    Mesh,
    ParticleArrays,
    Scene,
    SceneError,
    Simulation,
    SimulationError,
    SurfaceError,
    __version__,
    builtin_scenes,
    cuda_available,
    cuda_built,
    frame_formats,
    load_scene,
    mesh_formats,
)

__all__ = [
    "BlowUpError",
    "BusyError",
    "FrameWriter",
    "IoError",
    "Mesh",
    "ParticleArrays",
    "Scene",
    "SceneError",
    "Simulation",
    "SimulationError",
    "SurfaceError",
    "__version__",
    "builtin_scenes",
    "cuda_available",
    "cuda_built",
    "frame_formats",
    "load_scene",
    "mesh_formats",
]
