"""The module against the weir command: the same scene run both ways gives the same particles,
the same frame files, the same errors."""

import numpy as np
import pytest

import weir

FRAMES = 3


@pytest.fixture(scope="module")
def cli_frames(cli, tmp_path_factory):
    """The CLI's CSV frames of a small CPU dam break (frames 0..3)."""
    out = tmp_path_factory.mktemp("cli") / "dam_break"
    cli("run", "dam_break", "--backend", "cpu", "--particles", "2000", "--frames", FRAMES,
        "--format", "csv", "--quiet", "--out", out)
    return out


def read_csv(path):
    table = np.genfromtxt(path, delimiter=",", names=True, dtype=np.float32)
    return {name: table[name] for name in table.dtype.names}


def test_arrays_equal_the_clis_frames(cli_frames):
    sim = weir.Simulation("dam_break", backend="cpu", particles=2000)
    for k in range(FRAMES + 1):
        sim.advance_to(k * sim.frame_interval)
        frame = read_csv(cli_frames / f"frame_{k:05d}.csv")
        n = len(frame["x"])
        assert sim.particle_count == n
        x, v = sim.positions(), sim.velocities()
        # The same engine on the same scene, steps and threads: the same floats, exactly (CSV
        # holds each float's shortest text that reads back to it).
        np.testing.assert_array_equal(x, np.stack([frame["x"], frame["y"], frame["z"]], axis=1))
        np.testing.assert_array_equal(v,
                                      np.stack([frame["vx"], frame["vy"], frame["vz"]], axis=1))
        np.testing.assert_array_equal(sim.density(), frame["density"])
        np.testing.assert_array_equal(sim.pressure(), frame["pressure"])
    assert sim.step_count > 50


@pytest.mark.parametrize("format", ["vtu", "ply", "csv"])
def test_frame_files_are_the_clis_byte_for_byte(cli, tmp_path, format):
    cli("run", "dam_break", "--backend", "cpu", "--particles", "1500", "--frames", 2,
        "--format", format, "--quiet", "--out", tmp_path / "cli")
    sim = weir.Simulation("dam_break", backend="cpu", particles=1500)
    sim.run(frames=2, out=str(tmp_path / "py"), format=format)
    names = [f"frame_{k:05d}.{format}" for k in range(3)] + ["frames.json"]
    if format == "vtu":
        names.append("frame.pvd")
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_meshes_are_the_clis_byte_for_byte(cli, tmp_path):
    cli("run", "dam_break", "--backend", "cpu", "--particles", "1500", "--frames", 1,
        "--mesh", "--quiet", "--out", tmp_path / "cli")
    sim = weir.Simulation("dam_break", backend="cpu", particles=1500)
    sim.run(frames=1, out=str(tmp_path / "py"), mesh=["obj", "ply"])
    for k in range(2):
        for ext in ("obj", "ply"):
            name = f"mesh/surface_{k:05d}.{ext}"
            assert (tmp_path / "py" / name).read_bytes() == \
                (tmp_path / "cli" / name).read_bytes(), name


def test_the_dfsph_solver_agrees_with_the_cli_too(cli, tmp_path):
    cli("run", "dam_break", "--backend", "cpu", "--particles", "1000", "--frames", 1,
        "--solver", "dfsph", "--format", "csv", "--quiet", "--out", tmp_path / "cli")
    sim = weir.Simulation("dam_break", backend="cpu", particles=1000, solver="dfsph")
    sim.advance_to(sim.frame_interval)
    frame = read_csv(tmp_path / "cli" / "frame_00001.csv")
    np.testing.assert_array_equal(sim.positions()[:, 0], frame["x"])
    np.testing.assert_array_equal(sim.density(), frame["density"])
