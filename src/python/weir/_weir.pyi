"""weir: SPH fluid simulation on the CPU (OpenMP) and NVIDIA GPUs (CUDA)."""

from collections.abc import Callable, Sequence
import os
from typing import Any

import numpy
from numpy.typing import NDArray


class SceneError(ValueError):
    """
    A scene that cannot be read or run (names the file, the field, the bad value and what is allowed).
    """

class IoError(OSError):
    """A frame, mesh or index file that cannot be written or read."""

class SimulationError(RuntimeError):
    """
    A simulation that cannot be made or run (not enough memory, no CUDA device).
    """

class SurfaceError(ValueError):
    """Particles a surface cannot be built from."""

class BlowUpError(RuntimeError):
    """
    The simulation blew up; the message is the diagnosis (step, time, particle, likely cause), as weir run prints it.
    """

class BusyError(RuntimeError):
    """
    A call on a simulation that another thread is stepping (or reading): one call at a time on one simulation.
    """

def frame_formats() -> list[str]:
    """
    The particle frame formats, as weir run --format names them (the first is the default).
    """

def mesh_formats() -> list[str]:
    """The surface mesh formats, as weir mesh --format names them."""

def cuda_available() -> bool:
    """
    True when this module has the CUDA backend and a CUDA device is visible.
    """

def cuda_built() -> bool:
    """True when this module was built with the CUDA backend."""

class Scene:
    """
    A scene: container, fluid, obstacles, resolution and timing, read and checked as weir run reads a scene file. Immutable: the with_* methods return a new scene.
    """

    @staticmethod
    def from_file(path: str) -> Scene:
        """
        Reads a scene file (JSON). Raises SceneError naming the file, the field, the bad value and what is allowed.
        """

    @staticmethod
    def from_json(text: str, source: str = '<json>') -> Scene:
        """
        Reads a scene from JSON text; `source` names it in error messages, and mesh obstacle paths are relative to its folder.
        """

    @staticmethod
    def from_dict(fields: dict, source: str = '<dict>') -> Scene:
        """Reads a scene from a dict of scene fields (as in a scene file)."""

    @staticmethod
    def builtin(name: str) -> Scene:
        """A built-in scene by name (weir.builtin_scenes() lists them)."""

    def with_overrides(self, overrides: dict[str, Any] | str) -> Scene:
        """
        The scene with `overrides` (a dict of scene fields, or its JSON text) merged in, field by field (a JSON merge patch: nested dicts merge, other values replace, None removes a field), then checked again: e.g. {'fluid': {'viscosity': 0.01}}.
        """

    def with_model(self, model: str) -> Scene:
        """
        The scene with fluid.model set ('delta-sph' or 'paper'); the defaults that follow the model follow it.
        """

    def with_solver(self, solver: str) -> Scene:
        """The scene with its pressure solver set ('wcsph' or 'dfsph')."""

    def to_dict(self) -> dict[str, Any]:
        """The scene's fields as read (a dict, as in a scene file)."""

    @property
    def json(self) -> str:
        """The scene as read, compact JSON text."""

    @property
    def name(self) -> str:
        """The scene's name."""

    @property
    def source(self) -> str:
        """
        Where it came from: a file path, '<built-in NAME>', '<json>' or '<dict>'.
        """

    @property
    def description(self) -> str:
        """The scene's description, free text."""

    @property
    def model(self) -> str:
        """The fluid model: 'delta-sph' or 'paper'."""

    @property
    def solver(self) -> str:
        """The pressure solver: 'wcsph' or 'dfsph'."""

    @property
    def duration(self) -> float:
        """Simulated seconds a run covers (time.duration)."""

    @property
    def frame_rate(self) -> float:
        """Frames per simulated second (time.frameRate)."""

    def __repr__(self) -> str: ...

def load_scene(scene: Scene | str | os.PathLike[str] | dict[str, Any]) -> Scene:
    """
    A scene from a file path or built-in scene name (as weir run SCENE takes it), a pathlib.Path, a dict of scene fields, or a Scene (returned as is). Raises SceneError naming the file, the field and the value, with a did-you-mean for a near name.
    """

def builtin_scenes() -> list[str]:
    """The names of the built-in scenes."""

class ParticleArrays:
    """
    The particle arrays where the simulation keeps them (GPU memory for a CUDA run), without a copy, in the current cell order (ids says which particle each row is). Each array supports DLPack (__dlpack__, __dlpack_device__): cupy.from_dlpack, torch.from_dlpack, jax.dlpack.from_dlpack and numpy.from_dlpack (CPU) take it without copying. Valid until the next step; they keep the simulation alive.
    """

    @property
    def positions(self) -> object:
        """(n, 4) x, y, z [m] and a marker, float32 (float64 in a double build)."""

    @property
    def velocities(self) -> object:
        """(n, 4) vx, vy, vz [m/s] and density [kg/m^3]."""

    @property
    def ids(self) -> object:
        """
        (n,) int32: each row's particle id (its index in the initial, original order).
        """

    @property
    def count(self) -> int:
        """Particles n."""

    @property
    def on_device(self) -> bool:
        """True for CUDA device memory."""

    @property
    def device_id(self) -> int:
        """The CUDA device ordinal (0 on the CPU)."""

class Mesh:
    """
    A triangle mesh of the fluid's surface (marching cubes), as weir mesh writes it.
    """

    @property
    def vertices(self) -> NDArray[numpy.float32]:
        """(V, 3) float32 vertex positions [m]."""

    @property
    def normals(self) -> NDArray[numpy.float32]:
        """(V, 3) float32 unit normals, out of the fluid."""

    @property
    def triangles(self) -> NDArray[numpy.uint32]:
        """(T, 3) uint32 vertex indices, counter-clockwise seen from outside."""

    @property
    def vertex_count(self) -> int:
        """V."""

    @property
    def triangle_count(self) -> int:
        """T."""

    def write(self, path: str | os.PathLike, format: str | None = None) -> None:
        """
        Writes the mesh atomically; the format ('obj' or 'ply', weir.mesh_formats()) from the file's extension unless given. Raises IoError.
        """

class FrameWriter:
    """
    Writes numbered particle frames (<dir>/frame_00000.vtu, ...) in one format with frames.json, and frame.pvd for vtu, as weir run does: weir render and weir mesh read the folder.
    """

    def __init__(self, directory: str | os.PathLike, format: str = 'vtu', base_name: str = 'frame') -> None:
        """
        Creates the folder and its parents (IoError if impossible); format: weir.frame_formats().
        """

    def write(self, simulation: Simulation, index: int) -> None:
        """
        Writes the simulation's current state as frame `index` (at its current time), atomically; writing an index again replaces it. Raises IoError.
        """

    def path(self, index: int) -> str:
        """The file of frame `index`."""

    @property
    def directory(self) -> str: ...

    @property
    def format(self) -> str: ...

    @property
    def index_path(self) -> str:
        """<directory>/frames.json."""

class Simulation:
    """
    A simulation of a scene, set up as weir run sets it up (the same derived parameters, checks and errors). Stepping releases the GIL; a blow-up raises BlowUpError with the diagnosis. One call at a time: a call from another thread while one steps raises BusyError.
    """

    def __init__(self, scene: Scene | str | os.PathLike[str] | dict[str, Any], *, backend: str = 'auto', solver: str | None = None, model: str | None = None, particles: int | None = None, neighbours: str = 'auto', overrides: dict[str, Any] | str | None = None) -> None:
        """
        scene: a Scene, a file path or built-in name, or a dict (weir.load_scene). backend: 'auto' (the GPU when one is visible), 'cpu' or 'cuda'. solver: 'wcsph' or 'dfsph' (None: the scene's). model: 'delta-sph' or 'paper' (None: the scene's). particles: about this many particles (None: the scene's resolution). neighbours: 'auto', 'dense', 'grid' or 'brute'. overrides: a dict of scene fields merged into the scene (Scene.with_overrides). Raises SceneError, SimulationError or ValueError as weir run reports them.
        """

    def step(self, n: int = 1) -> None:
        """
        Advances n time steps in one call into the engine (no copies), then reads the fault record once (raises BlowUpError). Releases the GIL.
        """

    def advance_to(self, time: float) -> None:
        """
        Advances until the simulated time is `time` seconds (the last step cut to land on it), as weir run does between frames. Raises BlowUpError. Releases the GIL.
        """

    def run(self, frames: int | None = None, on_frame: Callable[[Simulation, int, float], object] | None = None, out: str | os.PathLike[str] | None = None, format: str = 'vtu', mesh: Sequence[str] = []) -> None:
        """
        Runs frame by frame, as weir run: frames lie at multiples of the scene's frame interval; the current state is the first when it lies on one. frames: how many after the first (None: to the scene's duration). on_frame(sim, index, time) is called after each frame. out: a folder to write frames to (format: weir.frame_formats()), mesh: mesh formats to write each frame's surface in, to out/mesh/surface_NNNNN.EXT. Raises BlowUpError (frames already written are kept).
        """

    def positions(self) -> NDArray[numpy.float32]:
        """
        (n, 3) positions [m] in the original particle order (row i is particle id i); a copy. The particles are downloaded once per state, whichever array asks first.
        """

    def velocities(self) -> NDArray[numpy.float32]:
        """(n, 3) velocities [m/s], original order; a copy."""

    def density(self) -> NDArray[numpy.float32]:
        """(n,) density [kg/m^3], original order; a copy."""

    def pressure(self) -> NDArray[numpy.float32]:
        """
        (n,) pressure [Pa] from the density by the equation of state, original order; a copy (as frames hold it).
        """

    def ids(self) -> NDArray[numpy.int32]:
        """
        (n,) int32 ids of the rows of the other arrays: 0 .. n - 1, as they are in the original order; with emitters or sinks, the live particles' ids in increasing order (an emitted particle gets a fresh id; ids are never reused).
        """

    def particle_arrays(self) -> ParticleArrays:
        """
        The arrays where they live, without a copy (ParticleArrays: DLPack views, on the GPU for a CUDA run), in cell order; waits for queued GPU work first.
        """

    def surface(self, backend: str | None = None, spacing: float | None = None, cell_size: float = 0.0, iso: float = 0.0, field: str = 'isotropic') -> Mesh:
        """
        The fluid's surface now, by marching cubes (as weir mesh): spacing None takes the run's particle spacing, cell_size 0 half of it, iso in particle spacings (> 0 inflates), field 'isotropic' or 'anisotropic' (weir mesh --surface-field); backend None: the simulation's.
        """

    def write_frame(self, path: str | os.PathLike, format: str | None = None) -> None:
        """
        Writes the current state to one frame file (format from the extension unless given: weir.frame_formats()); FrameWriter writes numbered series.
        """

    def explain(self) -> dict:
        """
        The derived parameters (what weir run --explain prints) as a dict: spacing, smoothing_radius, speed_of_sound, time_step, stiffness, viscosity, mass, steps_per_frame, frames, ... and 'lines', the explanation, one per decision, and 'warnings'.
        """

    @property
    def fault(self) -> str | None:
        """The first fault's diagnosis, or None."""

    @property
    def time(self) -> float:
        """Simulated time, s."""

    @property
    def step_count(self) -> int:
        """Steps taken."""

    @property
    def particle_count(self) -> int: ...

    @property
    def backend(self) -> str:
        """'cpu' or 'cuda'."""

    @property
    def device_name(self) -> str: ...

    @property
    def solver(self) -> str:
        """The pressure solver: 'wcsph' or 'dfsph'."""

    @property
    def neighbours(self) -> str: ...

    @property
    def scene(self) -> Scene:
        """The scene as run (with the solver, model and overrides applied)."""

    @property
    def spacing(self) -> float:
        """Particle spacing d, m."""

    @property
    def frame_interval(self) -> float:
        """Simulated seconds between frames, s."""

    @property
    def frame_count(self) -> int:
        """Frames of the scene's duration after frame 0."""

    def __repr__(self) -> str: ...
