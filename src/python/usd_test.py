"""The USD stage weir writes (weir run --usd, weir usd), read back with Pixar's USD (usd-core from
PyPI): time samples, particle points, velocities and ids as in the frame files, the surface mesh
with per-vertex velocities, the container and obstacles."""

import json

import numpy as np
import pytest

Usd = pytest.importorskip(
    "pxr.Usd", reason="usd-core (PyPI) is not installed; scripts/setup.sh installs it")
from pxr import UsdGeom  # noqa: E402

# A small dam break with an obstacle box and sphere: 144 particles at 2 cm.
SCENE = {
    "name": "tiny_usd",
    "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.08]},
    "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.08]}],
    "obstacles": {"boxes": [{"min": [0.2, 0, 0.02], "max": [0.25, 0.05, 0.06]}],
                  "spheres": [{"center": [0.2, 0.15, 0.04], "radius": 0.02}]},
    "particles": {"spacing": 0.02},
    "time": {"duration": 1, "frameRate": 30},
}


@pytest.fixture(scope="module")
def run(cli, tmp_path_factory):
    """weir run --usd --mesh, CSV frames numbered from 1 (frames 1..4)."""
    root = tmp_path_factory.mktemp("usd")
    (root / "scene.json").write_text(json.dumps(SCENE))
    out = root / "out"
    cli("run", root / "scene.json", "--backend", "cpu", "--quiet", "--frames", 3, "--format",
        "csv", "--first-frame-number", 1, "--mesh", "--mesh-format", "ply", "--usd", "--out", out)
    return out


def read_csv(path):
    table = np.genfromtxt(path, delimiter=",", names=True, dtype=np.float32)
    return {name: table[name] for name in table.dtype.names}


def test_stage_has_the_runs_frames_as_time_samples(run):
    stage = Usd.Stage.Open(str(run / "frames.usda"))
    assert stage.GetStartTimeCode() == 1 and stage.GetEndTimeCode() == 4
    assert stage.GetTimeCodesPerSecond() == pytest.approx(30)
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1
    assert stage.GetDefaultPrim().GetPath() == "/weir"
    points = UsdGeom.Points(stage.GetPrimAtPath("/weir/particles"))
    assert points, "no Points prim /weir/particles"
    assert points.GetPointsAttr().GetTimeSamples() == [1, 2, 3, 4]
    for number in (1, 4):
        frame = read_csv(run / f"frame_{number:05d}.csv")
        x = np.array(points.GetPointsAttr().Get(number))
        v = np.array(points.GetVelocitiesAttr().Get(number))
        np.testing.assert_array_equal(x, np.stack([frame["x"], frame["y"], frame["z"]], axis=1))
        np.testing.assert_array_equal(v,
                                      np.stack([frame["vx"], frame["vy"], frame["vz"]], axis=1))
        np.testing.assert_array_equal(np.array(points.GetIdsAttr().Get(number)), frame["id"])
        density = UsdGeom.PrimvarsAPI(points).GetPrimvar("density")
        assert density.GetInterpolation() == UsdGeom.Tokens.vertex
        np.testing.assert_array_equal(np.array(density.Get(number)), frame["density"])
        lo, hi = np.array(points.GetExtentAttr().Get(number))
        assert np.all(lo <= x.min(axis=0)) and np.all(hi >= x.max(axis=0))
    assert len(points.GetIdsAttr().Get(1)) == 144
    assert list(points.GetWidthsAttr().Get()) == [pytest.approx(0.02)]
    assert points.GetWidthsInterpolation() == UsdGeom.Tokens.constant
    # Frame 4 moved: the stage is not one frame repeated.
    assert not np.array_equal(points.GetPointsAttr().Get(1), points.GetPointsAttr().Get(4))


def test_surface_mesh_has_per_vertex_velocities(run):
    stage = Usd.Stage.Open(str(run / "frames.usda"))
    mesh = UsdGeom.Mesh(stage.GetPrimAtPath("/weir/surface"))
    assert mesh, "no Mesh prim /weir/surface"
    assert mesh.GetSubdivisionSchemeAttr().Get() == UsdGeom.Tokens.none
    for number in (1, 4):
        x = np.array(mesh.GetPointsAttr().Get(number))
        counts = np.array(mesh.GetFaceVertexCountsAttr().Get(number))
        indices = np.array(mesh.GetFaceVertexIndicesAttr().Get(number))
        v = np.array(mesh.GetVelocitiesAttr().Get(number))
        assert len(x) > 100 and np.all(counts == 3) and len(indices) == 3 * len(counts)
        assert indices.min() >= 0 and indices.max() < len(x)
        assert v.shape == x.shape and len(mesh.GetNormalsAttr().Get(number)) == len(x)
        # The mesh of weir mesh's PLY file, vertex for vertex.
        ply = (run / "mesh" / f"surface_{number:05d}.ply").read_bytes()
        assert f"element vertex {len(x)}\n".encode() in ply
        # A vertex's velocity is a weighted mean of particle velocities: never faster than the
        # fastest particle; at rest (frame 1) zero.
        frame = read_csv(run / f"frame_{number:05d}.csv")
        fastest = np.sqrt(frame["vx"] ** 2 + frame["vy"] ** 2 + frame["vz"] ** 2).max()
        assert np.linalg.norm(v, axis=1).max() <= fastest * (1 + 1e-5)
        if number == 1:
            assert np.all(v == 0)
        else:
            assert np.mean(v[:, 1]) < -0.05  # the column falls
    assert mesh.GetPointsAttr().GetTimeSamples() == [1, 2, 3, 4]


def test_container_and_obstacles_are_in_place(run):
    stage = Usd.Stage.Open(str(run / "frames.usda"))

    def world_box(path):
        prim = stage.GetPrimAtPath(path)
        assert prim, f"no prim {path}"
        cache = UsdGeom.BBoxCache(Usd.TimeCode.Default(),
                                  [UsdGeom.Tokens.default_, UsdGeom.Tokens.guide])
        box = cache.ComputeWorldBound(prim).ComputeAlignedRange()
        return np.array(box.GetMin()), np.array(box.GetMax())

    container = stage.GetPrimAtPath("/weir/container")
    assert container.GetTypeName() == "Cube"
    assert UsdGeom.Imageable(container).GetPurposeAttr().Get() == UsdGeom.Tokens.guide
    for path, lo, hi in [("/weir/container", [0, 0, 0], [0.3, 0.2, 0.08]),
                         ("/weir/obstacles/box_0", [0.2, 0, 0.02], [0.25, 0.05, 0.06]),
                         ("/weir/obstacles/sphere_0", [0.18, 0.13, 0.02], [0.22, 0.17, 0.06])]:
        got_lo, got_hi = world_box(path)
        np.testing.assert_allclose(got_lo, lo, atol=1e-6, err_msg=path)
        np.testing.assert_allclose(got_hi, hi, atol=1e-6, err_msg=path)
    assert stage.GetPrimAtPath("/weir/obstacles/sphere_0").GetTypeName() == "Sphere"


def test_weir_usd_rewrites_a_selection_and_refuses_a_damaged_frame(cli, run, tmp_path):
    stage_path = tmp_path / "two.usda"
    cli("usd", run, "--frames", "2:3", "--no-meshes", "--out", stage_path)
    stage = Usd.Stage.Open(str(stage_path))
    assert stage.GetStartTimeCode() == 2 and stage.GetEndTimeCode() == 3
    assert not stage.GetPrimAtPath("/weir/surface")
    assert UsdGeom.Points(stage.GetPrimAtPath("/weir/particles")).GetPointsAttr() \
        .GetTimeSamples() == [2, 3]

    damaged = tmp_path / "damaged"
    damaged.mkdir()
    for name in ["frames.json", "frame_00001.csv", "frame_00002.csv"]:
        (damaged / name).write_bytes((run / name).read_bytes())
    text = (damaged / "frame_00002.csv").read_text()
    cut = len(text) // 2
    while text[cut - 1] == "\n":  # end mid-line: a truncated file, not a shorter one
        cut += 1
    (damaged / "frame_00002.csv").write_text(text[:cut])
    done = cli("usd", damaged, "--frames", "1:2", check=False)
    assert done.returncode == 1
    assert "frame_00002.csv" in done.stderr and "cannot read" in done.stderr
    # Nothing half-written is left: no stage, no temporaries.
    assert sorted(p.name for p in damaged.iterdir()) == ["frame_00001.csv", "frame_00002.csv",
                                                         "frames.json"]


def test_non_finite_values_stay_readable(cli, tmp_path):
    """A frame (written by another tool) whose velocities hold NaN of either sign and infinities:
    the stage still opens, with the same values (USD reads 'nan', not '-nan')."""
    frames = tmp_path / "frames"
    frames.mkdir()
    (frames / "frames.json").write_text(
        json.dumps({"frames": [{"index": 0, "time": 0, "file": "frame_00000.csv"}]}))
    (frames / "frame_00000.csv").write_text(
        "x,y,z,vx,vy,vz,density,pressure,id\n"
        "0,0,0,nan,-nan,inf,1000,0,0\n"
        "0.02,0,0,-inf,1,2,1000,0,1\n")
    cli("usd", frames, "--spacing", 0.02)
    stage = Usd.Stage.Open(str(frames / "frames.usda"))
    v = np.array(UsdGeom.Points(stage.GetPrimAtPath("/weir/particles")).GetVelocitiesAttr().Get(0))
    assert np.isnan(v[0, 0]) and np.isnan(v[0, 1]) and v[0, 2] == np.inf
    assert v[1, 0] == -np.inf and list(v[1, 1:]) == [1, 2]


def test_a_scenes_mesh_obstacle_is_placed(cli, repo, tmp_path):
    """examples/showcase.json's rock (an OBJ scaled by 0.1 and moved to (0.6, 0, 0.3)) becomes a
    Mesh with the file's faces where the scene puts it."""
    out = tmp_path / "showcase"
    cli("run", repo / "examples" / "showcase.json", "--backend", "cpu", "--particles", 3000,
        "--frames", 0, "--quiet", "--usd", "--out", out)
    stage = Usd.Stage.Open(str(out / "frames.usda"))
    rock = UsdGeom.Mesh(stage.GetPrimAtPath("/weir/obstacles/mesh_0"))
    assert rock, "no Mesh /weir/obstacles/mesh_0"
    obj = (repo / "examples" / "rock.obj").read_text().splitlines()
    vertices = np.array([[float(x) for x in line.split()[1:4]] for line in obj
                         if line.startswith("v ")])
    assert len(rock.GetPointsAttr().Get()) == len(vertices)
    assert len(rock.GetFaceVertexCountsAttr().Get()) == sum(l.startswith("f ") for l in obj)
    np.testing.assert_allclose(np.array(rock.GetPointsAttr().Get()),
                               vertices * 0.1 + [0.6, 0, 0.3], atol=1e-6)


def test_rigid_bodies_move_by_their_poses(cli, tmp_path):
    """A floating box and a turning paddle (issue 18): each a /weir/bodies/body_N Xform whose
    translate and orient follow frames.json's poses frame by frame, holding its shape."""
    scene = {
        "name": "usd_bodies",
        "fluid": {"preset": "water"},
        "container": {"min": [0, 0, 0], "max": [0.4, 0.3, 0.2]},
        "blocks": [{"min": [0, 0, 0], "max": [0.4, 0.1, 0.2]}],
        "bodies": [
            {"box": {"min": [0.05, 0.15, 0.06], "max": [0.13, 0.21, 0.14]}, "density": 600},
            {"sphere": {"center": [0.3, 0.05, 0.1], "radius": 0.03},
             "motion": {"rotate": {"rate": [0, 0, 4]}}}],
        "particles": {"spacing": 0.02},
        "time": {"duration": 0.1, "frameRate": 30},
    }
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    out = tmp_path / "out"
    cli("run", tmp_path / "scene.json", "--backend", "cpu", "--quiet", "--format", "csv",
        "--usd", "--out", out)
    index = json.loads((out / "frames.json").read_text())
    stage = Usd.Stage.Open(str(out / "frames.usda"))
    for k in range(2):
        body = stage.GetPrimAtPath(f"/weir/bodies/body_{k}")
        assert body, f"no /weir/bodies/body_{k}"
        xform = UsdGeom.Xformable(body)
        translate = body.GetAttribute("xformOp:translate")
        orient = body.GetAttribute("xformOp:orient")
        for frame in index["frames"]:
            pose = frame["bodies"][k]
            np.testing.assert_allclose(np.array(translate.Get(frame["index"])), pose["position"],
                                       atol=1e-6)
            q = orient.Get(frame["index"])
            np.testing.assert_allclose([q.GetReal(), *q.GetImaginary()],
                                       [pose["orientation"][3], *pose["orientation"][:3]],
                                       atol=1e-6)
        assert xform.GetOrderedXformOps()
    box = UsdGeom.Cube(stage.GetPrimAtPath("/weir/bodies/body_0/shape"))
    assert box and box.GetSizeAttr().Get() == 1
    np.testing.assert_allclose(np.array(box.GetPrim().GetAttribute("xformOp:scale").Get()),
                               [0.08, 0.06, 0.08], atol=1e-6)
    ball = UsdGeom.Sphere(stage.GetPrimAtPath("/weir/bodies/body_1/shape"))
    assert ball and abs(ball.GetRadiusAttr().Get() - 0.03) < 1e-9
    # The box fell; the paddle turned about z (its quaternion's z part grows).
    first, last = index["frames"][0], index["frames"][-1]
    assert last["bodies"][0]["position"][1] < first["bodies"][0]["position"][1]
    assert abs(orient_z := last["bodies"][1]["orientation"][2]) > 0.1, orient_z
