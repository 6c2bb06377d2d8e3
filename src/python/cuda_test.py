"""The CUDA backend from Python and DLPack on the GPU: skipped where no CUDA device is visible.
On a GPU machine: scripts/test.sh runs them (or pytest src/python/cuda_test.py)."""

import numpy as np
import pytest

import weir

pytestmark = pytest.mark.skipif(not weir.cuda_available(),
                                reason="no CUDA device visible (or a module built without CUDA)")


@pytest.fixture(scope="module")
def pair():
    """The same dam break on the GPU and the CPU, advanced to the same time."""
    gpu = weir.Simulation("dam_break", backend="cuda", particles=20_000)
    cpu = weir.Simulation("dam_break", backend="cpu", particles=20_000)
    for sim in (gpu, cpu):
        sim.advance_to(0.05)
    return gpu, cpu


def test_the_gpu_agrees_with_the_cpu(pair):
    gpu, cpu = pair
    assert gpu.backend == "cuda" and gpu.particle_count == cpu.particle_count
    assert gpu.time == pytest.approx(0.05, abs=1e-7)
    # Float rounding differs (reduction order, fused multiply-adds): positions agree within a
    # small share of the spacing this early, density within a fraction of a percent.
    d = gpu.spacing
    assert np.abs(gpu.positions() - cpu.positions()).max() < 0.05 * d
    assert np.abs(gpu.density() / cpu.density() - 1).max() < 2e-3


def test_particle_arrays_are_device_memory_through_dlpack(pair):
    gpu, _ = pair
    views = gpu.particle_arrays()
    assert views.on_device and views.count == gpu.particle_count
    assert views.positions.__dlpack_device__() == (2, views.device_id)  # kDLCUDA
    assert views.ids.__dlpack_device__() == (2, views.device_id)
    with pytest.raises(Exception):
        np.from_dlpack(views.positions)  # NumPy takes host memory only: no hidden copy


def test_cupy_reads_and_writes_the_state_without_a_copy():
    cupy = pytest.importorskip("cupy")
    sim = weir.Simulation("dam_break", backend="cuda", particles=20_000)
    sim.step(20)
    views = sim.particle_arrays()
    pos = cupy.from_dlpack(views.positions)
    ids = cupy.from_dlpack(views.ids)
    vel = cupy.from_dlpack(views.velocities)
    assert pos.shape == (sim.particle_count, 4)
    np.testing.assert_array_equal(cupy.asnumpy(pos[:, :3]), sim.positions()[cupy.asnumpy(ids)])
    vel[:, :3] = 0
    cupy.cuda.runtime.deviceSynchronize()
    np.testing.assert_array_equal(sim.velocities(), 0)


def test_torch_reads_the_state_without_a_copy():
    torch = pytest.importorskip("torch")
    sim = weir.Simulation("dam_break", backend="cuda", particles=20_000)
    sim.step(20)
    views = sim.particle_arrays()
    pos = torch.from_dlpack(views.positions)
    ids = torch.from_dlpack(views.ids)
    assert pos.is_cuda and tuple(pos.shape) == (sim.particle_count, 4)
    np.testing.assert_array_equal(pos[:, :3].cpu().numpy(),
                                  sim.positions()[ids.cpu().numpy()])


def test_jax_reads_the_state():
    jax = pytest.importorskip("jax")
    sim = weir.Simulation("dam_break", backend="cuda", particles=20_000)
    sim.step(5)
    views = sim.particle_arrays()
    pos = jax.dlpack.from_dlpack(views.positions)
    ids = np.asarray(jax.dlpack.from_dlpack(views.ids))
    np.testing.assert_array_equal(np.asarray(pos)[:, :3], sim.positions()[ids])


def test_a_blow_up_on_the_gpu_raises_with_the_diagnosis():
    thrown = {
        "name": "thrown",
        "container": {"min": [0, 0, 0], "max": [1.6, 1.0, 0.6]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.6, 0.6], "velocity": [1000, 0, 0]}],
        "fluid": {"restDensity": 1000},
        "particles": {"count": 5200},
        "time": {"duration": 1.0, "frameRate": 30, "timeStep": 0.001},
    }
    sim = weir.Simulation(thrown, backend="cuda")
    with pytest.raises(weir.BlowUpError, match="blew up at step"):
        sim.advance_to(0.5)


def test_the_surface_on_the_gpu_matches_the_cpus(pair):
    gpu, _ = pair
    on_gpu = gpu.surface(backend="cuda")
    on_cpu = gpu.surface(backend="cpu")
    assert abs(on_gpu.triangle_count - on_cpu.triangle_count) <= 0.01 * on_cpu.triangle_count
