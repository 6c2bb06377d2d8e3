"""Blender from Debian's package, headless, loads a small weir run with
tools/blender/weir_blender.py and renders a frame in Cycles on the CPU (docs/pipeline.md,
"Blender"): the surface mesh is the one weir wrote, with per-vertex `velocity` as weir's USD stage
has it; the particles keep their velocities and ids; Blender reads the OpenVDB grids, and the
level set meshes to weir's surface; the render shows the fluid where the camera sees it, and
motion blur moves what weir's velocities move. Skips where `blender` is not installed
(scripts/setup.sh installs it where apt can)."""

import json
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

BLENDER = shutil.which("blender")
TOOLS = pathlib.Path(__file__).resolve().parents[2] / "tools" / "blender"
pytestmark = pytest.mark.skipif(
    BLENDER is None, reason="blender is not installed (apt-get install blender; "
    "scripts/setup.sh installs it where it can)")

# Runs inside Blender: loads the run as the tool does, renders with motion blur, without it and
# without the fluid, and reports what Blender holds.
DRIVER = r"""
import json, sys
import bpy
import mathutils
from bpy_extras.object_utils import world_to_camera_view
args = json.loads(sys.argv[sys.argv.index("--") + 1])
sys.path.insert(0, args["tools"])
import weir_blender
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
made = weir_blender.load_run(args["run"], args["frame"])
made["particles"].hide_render = True
made["volume"].hide_render = True
scene = bpy.context.scene
camera = weir_blender.stage(made, width=96, height=64, samples=8, shutter=args["shutter"])
surface, particles, volume = made["surface"], made["particles"], made["volume"]
bpy.context.view_layer.update()
corners = [surface.matrix_world @ mathutils.Vector(c) for c in surface.bound_box]
view = [world_to_camera_view(scene, camera, c) for c in corners]

def attributes(mesh):
    return {a.name: [a.data_type, a.domain] for a in mesh.attributes if not a.name.startswith(".")}

def values(mesh, name, field, width):
    flat = [0.0] * (len(mesh.vertices) * width)
    mesh.attributes[name].data.foreach_get(field, flat)
    return flat

volume.data.grids.load()
# The VDB's level set as a mesh (what the tool draws for a run without surface meshes).
from_vdb = weir_blender.volume_surface(volume)
from_vdb.hide_render = True
bpy.context.view_layer.update()
evaluated = from_vdb.evaluated_get(bpy.context.evaluated_depsgraph_get())
# In weir's coordinates (the parent "weir" turns them to Blender's).
to_weir = made["root"].matrix_world.inverted() @ evaluated.matrix_world
vdb_points = [tuple(to_weir @ v.co) for v in evaluated.to_mesh().vertices]
report = {
    "build_usd": bool(bpy.app.build_options.usd),
    "build_openvdb": bool(bpy.app.build_options.openvdb),
    "frame": scene.frame_current,
    "fps": scene.render.fps / scene.render.fps_base,
    "surface": {"vertices": [tuple(v.co) for v in surface.data.vertices],
                "attributes": attributes(surface.data),
                "velocity": values(surface.data, "velocity", "vector", 3),
                "world_z": [min(c.z for c in corners), max(c.z for c in corners)]},
    "particles": {"count": len(particles.data.vertices),
                  "attributes": attributes(particles.data),
                  "id": values(particles.data, "id", "value", 1),
                  "velocity": values(particles.data, "velocity", "vector", 3)},
    "volume": {"grids": {g.name: g.data_type for g in volume.data.grids},
               "velocity_grid": volume.data.velocity_grid,
               "surface_box": [[min(p[a] for p in vdb_points) for a in range(3)],
                               [max(p[a] for p in vdb_points) for a in range(3)]],
               "file": volume.data.grids.frame_filepath},
    "view": [[v.x, v.y] for v in view],
    "motion_blur": scene.render.use_motion_blur,
}
# Opaque and dark blue for the test's few samples (glass is noise at 8 samples a pixel).
bsdf = surface.data.materials[0].node_tree.nodes["Principled BSDF"]
bsdf.inputs["Transmission"].default_value = 0.0
bsdf.inputs["Roughness"].default_value = 1.0
bsdf.inputs["Base Color"].default_value = (0.05, 0.2, 0.8, 1.0)
scene.render.motion_blur_shutter = args["shutter"]
for name, blur, shown in (("blur", True, True), ("sharp", False, True), ("empty", False, False)):
    scene.render.use_motion_blur = blur
    surface.hide_render = not shown
    scene.render.filepath = args["out"] + "/" + name + ".png"
    bpy.ops.render.render(write_still=True)
# The same motion-blurred render with the velocities zeroed: only the motion differs.
surface.hide_render = False
scene.render.use_motion_blur = True
zero = [0.0] * (3 * len(surface.data.vertices))
surface.data.attributes["velocity"].data.foreach_set("vector", zero)
surface.data.update()
scene.render.filepath = args["out"] + "/still.png"
bpy.ops.render.render(write_still=True)
json.dump(report, open(args["out"] + "/report.json", "w"))
"""

FRAME = 3
# The shutter in frames: 8 (long) so that the test frame's flow, up to 1.8 m/s, moves some pixels
# of the 96 x 64 picture while it is open (0.5, a 180-degree shutter, is the tool's default).
SHUTTER = 8.0


@pytest.fixture(scope="module")
def run(cli, tmp_path_factory):
    """A 3000-particle dam break, 3 frames: PLY particles, PLY and VDB surfaces, a USD stage."""
    out = tmp_path_factory.mktemp("blender") / "run"
    cli("run", "dam_break", "--backend", "cpu", "--quiet", "--particles", 3000, "--frames",
        FRAME, "--format", "ply", "--mesh", "--mesh-format", "ply,vdb", "--usd", "--out", out)
    return out


@pytest.fixture(scope="module")
def blender(run, tmp_path_factory):
    out = tmp_path_factory.mktemp("blender-out")
    driver = out / "driver.py"
    driver.write_text(DRIVER)
    args = {"tools": str(TOOLS), "run": str(run), "frame": FRAME,
            "shutter": SHUTTER, "out": str(out)}
    done = subprocess.run([BLENDER, "-b", "--factory-startup", "--python-exit-code", "1",
                           "--python", str(driver), "--", json.dumps(args)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and (out / "report.json").exists(), \
        f"blender exited {done.returncode}:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return json.loads((out / "report.json").read_text()), out


def read_ply(path):
    """weir's binary PLY: (vertex table as a structured array, triangle indices or None)."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    types = {"float": "<f4", "int": "<i4"}
    fields, count, faces = [], 0, 0
    for line in data[:end].decode().splitlines():
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            count = int(w[2])
        elif w[:2] == ["element", "face"]:
            faces = int(w[2])
        elif w[:1] == ["property"] and w[1] != "list":
            fields.append((w[2], types[w[1]]))
    vertices = np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)
    offset = end + vertices.nbytes
    triangles = None
    if faces:
        record = np.dtype([("n", "u1"), ("i", "<u4", 3)])
        triangles = np.frombuffer(data, dtype=record, count=faces, offset=offset)["i"]
    return vertices, triangles


def image(path):
    import matplotlib.image

    return matplotlib.image.imread(str(path))[..., :3].astype(np.float64)


def test_blender_reads_the_surface_as_weir_wrote_it(run, blender):
    report, _ = blender
    mesh, _ = read_ply(run / "mesh" / f"surface_{FRAME:05d}.ply")
    positions = np.stack([mesh["x"], mesh["y"], mesh["z"]], axis=1)
    loaded = np.array(report["surface"]["vertices"])
    np.testing.assert_allclose(loaded, positions, atol=1e-6)
    assert report["frame"] == FRAME and report["fps"] == pytest.approx(30)
    # Its extent is the fluid's: the frame's particles, with the surface up to about a particle
    # spacing outside their centres.
    particles, _ = read_ply(run / f"frame_{FRAME:05d}.ply")
    spacing = json.loads((run / "frames.json").read_text())["spacing"]
    centres = np.stack([particles["x"], particles["y"], particles["z"]], axis=1)
    below = centres.min(axis=0) - loaded.min(axis=0)
    above = loaded.max(axis=0) - centres.max(axis=0)
    assert np.all(below > -0.5 * spacing) and np.all(below < 1.5 * spacing), below / spacing
    assert np.all(above > -0.5 * spacing) and np.all(above < 1.5 * spacing), above / spacing
    # weir's y up is Blender's z up.
    assert report["surface"]["world_z"] == pytest.approx([loaded[:, 1].min(), loaded[:, 1].max()],
                                                         abs=1e-5)


def test_the_surface_carries_velocities_for_motion_blur(run, blender):
    report, _ = blender
    assert report["surface"]["attributes"]["velocity"] == ["FLOAT_VECTOR", "POINT"]
    assert report["motion_blur"]
    v = np.array(report["surface"]["velocity"]).reshape(-1, 3)
    # Each vertex moves as the particles near it: compare with the nearest particle's velocity.
    particles, _ = read_ply(run / f"frame_{FRAME:05d}.ply")
    centres = np.stack([particles["x"], particles["y"], particles["z"]], axis=1)
    velocities = np.stack([particles["vx"], particles["vy"], particles["vz"]], axis=1)
    vertices = np.array(report["surface"]["vertices"])
    nearest = np.concatenate([
        np.argmin(((chunk[:, None, :] - centres[None, :, :]) ** 2).sum(-1), axis=1)
        for chunk in np.array_split(vertices, len(vertices) // 256 + 1)])
    speed = np.linalg.norm(velocities, axis=1)
    assert speed.max() > 0.5, "the test frame should move"
    difference = np.linalg.norm(v - velocities[nearest], axis=1)
    assert np.median(difference) < 0.1 * speed.max(), (np.median(difference), speed.max())
    # The collapsing column falls: the top of the surface moves down, as its particles do.
    top = vertices[:, 1] > np.percentile(vertices[:, 1], 90)
    assert v[top, 1].mean() < -0.2


def test_the_surface_velocities_are_those_of_weirs_usd_stage(run, blender):
    """The script computes the vertices' velocities as weir does for its USD stage's surface."""
    Usd = pytest.importorskip("pxr.Usd", reason="usd-core (PyPI) is not installed")
    from pxr import UsdGeom

    report, _ = blender
    stage = Usd.Stage.Open(str(run / "frames.usda"))
    mesh = UsdGeom.Mesh(stage.GetPrimAtPath("/weir/surface"))
    np.testing.assert_allclose(np.array(mesh.GetPointsAttr().Get(FRAME)),
                               report["surface"]["vertices"], atol=1e-6)
    np.testing.assert_allclose(np.array(report["surface"]["velocity"]).reshape(-1, 3),
                               np.array(mesh.GetVelocitiesAttr().Get(FRAME)), atol=1e-4)


def test_blender_keeps_the_particles_ids_and_velocities(run, blender):
    report, _ = blender
    particles, _ = read_ply(run / f"frame_{FRAME:05d}.ply")
    loaded = report["particles"]
    assert loaded["count"] == len(particles)
    for name, kind in (("velocity", "FLOAT_VECTOR"), ("id", "INT"), ("density", "FLOAT"),
                       ("pressure", "FLOAT")):
        assert loaded["attributes"][name] == [kind, "POINT"]
    np.testing.assert_array_equal(loaded["id"], particles["id"])
    np.testing.assert_allclose(np.array(loaded["velocity"]).reshape(-1, 3),
                               np.stack([particles["vx"], particles["vy"], particles["vz"]], 1),
                               atol=1e-6)


def test_blender_opens_the_vdb_with_weirs_grids(run, blender):
    report, _ = blender
    assert report["build_openvdb"]
    volume = report["volume"]
    assert volume["file"].endswith(f"surface_{FRAME:05d}.vdb")
    assert volume["grids"]["surface"] == "FLOAT"
    assert volume["grids"]["velocity"] == "VECTOR_FLOAT"
    assert volume["velocity_grid"] == "velocity"
    # Its level set, meshed by Blender's Volume to Mesh, lies where weir's surface mesh does
    # (the tool moves the volume back by the half voxel Blender 3.4 shifts it; a voxel is half a
    # particle spacing).
    mesh, _ = read_ply(run / "mesh" / f"surface_{FRAME:05d}.ply")
    spacing = json.loads((run / "frames.json").read_text())["spacing"]
    lo = [mesh[a].min() for a in "xyz"]
    hi = [mesh[a].max() for a in "xyz"]
    np.testing.assert_allclose(volume["surface_box"], [lo, hi], atol=0.15 * spacing)
    if not report["build_usd"]:
        print("this Blender has no USD import (Debian's 3.4 is built without it); "
              "docs/pipeline.md uses meshes and VDB instead")


def test_the_render_shows_the_fluid_where_the_camera_sees_it(blender):
    report, out = blender
    fluid, empty = image(out / "sharp.png"), image(out / "empty.png")
    assert fluid.shape == (64, 96, 3)
    changed = np.abs(fluid - empty).max(axis=2) > 0.1
    # The surface's box, as the camera projects it, in pixels (rows from the top).
    view = np.array(report["view"])
    assert np.all((view > 0) & (view < 1)), "the camera frames the fluid"
    x0, x1 = np.floor(view[:, 0].min() * 96), np.ceil(view[:, 0].max() * 96)
    y0, y1 = np.floor((1 - view[:, 1].max()) * 64), np.ceil((1 - view[:, 1].min()) * 64)
    inside = np.zeros_like(changed)
    inside[int(y0):int(y1), int(x0):int(x1)] = True
    assert changed[inside].mean() > 0.3, "the fluid covers its box on screen"
    # Outside the box only its shadow and reflections change the picture.
    assert changed[~inside].mean() < 0.25 * changed[inside].mean()


def test_motion_blur_smears_the_moving_fluid(blender):
    _, out = blender
    blur, still, sharp, empty = (image(out / f"{n}.png") for n in ("blur", "still", "sharp",
                                                                   "empty"))
    # Motion blur with weir's velocities against the same render with them zeroed: the same
    # samples, so what differs is the motion.
    smeared = np.abs(blur - still).max(axis=2) > 0.1
    fluid = np.abs(sharp - empty).max(axis=2) > 0.1
    # Zeroed, the blur is gone: the picture is the one rendered without motion blur.
    assert not (np.abs(still - sharp).max(axis=2) > 0.1).any()
    assert smeared.sum() > 0.1 * fluid.sum(), (smeared.sum(), fluid.sum())
    # The smear lies on the fluid and a few pixels around it (where it moves), nowhere else.
    near = fluid.copy()
    for shift in range(1, 6):
        for axis in (0, 1):
            near |= np.roll(fluid, shift, axis=axis) | np.roll(fluid, -shift, axis=axis)
    assert not smeared[~near].any()
