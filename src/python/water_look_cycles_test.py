"""The water look against Blender Cycles: one frame of a small dam break, path traced by
`weir render --look water` and by Cycles (Debian's Blender, headless, on the CPU) from what weir
traced (`--export-water`: the water's triangles with their normals, the camera, the container's
floor and walls, the sky as an image, the sun and the constants), must give the same picture.

Both renderers' linear images go through weir's tone map (exposure, Narkowicz's ACES fit, sRGB)
here in NumPy. The metric: after a Gaussian blur of 1 pixel (both images are Monte-Carlo noisy),
the mean absolute difference of the 8-bit sRGB values, the mean SSIM (7 x 7 windows) of the
blurred images' luma, and the worst 10 x 10-pixel tile's mean absolute difference. The
thresholds lie between the noise floor (two weir images of independent paths) and weir against
Cycles on one side, and Cycles scenes wrong on purpose on the other (glass's index of refraction
instead of water's, a field of view 3 % wider, half the absorption, the sun as Cycles' own lamp
with its caustics): each of those must fail them.
docs/rendering.md, "Checked against Blender Cycles", gives the measured values and what differs
by design. Skips where `blender` is not installed (scripts/setup.sh installs it where apt can).
"""

import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

BLENDER = shutil.which("blender")
pytestmark = pytest.mark.skipif(
    BLENDER is None, reason="blender is not installed (apt-get install blender; "
    "scripts/setup.sh installs it where it can)")

FRAME = 12  # t = 0.4 s: the front has hit the far wall
WIDTH, HEIGHT = 160, 90
WEIR_PATHS = 512  # per pixel; a second image of 256, whose paths are the first half of these
CYCLES_SAMPLES = 256
CAMERA = ("--camera", "30,22,2.3", "--target", "0.85,0.3,0.3")  # docs/rendering.md's picture
# The thresholds, between the measured values (docs/rendering.md): the noise floor 0.33 levels,
# SSIM 0.998, worst tile 2.3 levels; weir against Cycles 0.59, 0.997, 3.6; the wrong scenes
# 1.22-2.02, 0.968-0.996, 12.3-23.5.
MAX_MEAN_DIFFERENCE = 1.2  # 8-bit levels, blurred
MIN_SSIM = 0.985  # blurred luma
MAX_WORST_TILE = 6.0  # 8-bit levels, blurred, the worst 10 x 10-pixel tile's mean
TILE = 10
# The scene as weir traced it, and two scenes that are wrong on purpose and must fail.
RIGHT = {"name": "cycles"}
WRONG = [{"name": "wrong_ior", "ior": 1.5},  # glass, not water
         {"name": "wrong_fov", "fov": 1.03},  # tan(field of view / 2) 3 % larger
         {"name": "wrong_absorption", "absorption": 0.5},  # half weir's
         # the sun as Cycles has it by default, not as weir models it (caustics of the sun)
         {"name": "lamp_sun", "lamp_sun": True}]
# Set to a folder to write the side-by-side picture of docs/rendering.md there.
PICTURES = os.environ.get("WEIR_CYCLES_PICTURES")

# Runs inside Blender: builds weir's traced scene in Cycles and renders it once per variant, as
# linear float RGB (raw little-endian, rows from the top).
DRIVER = r"""
import json, math, sys, array
import bpy
import mathutils

args = json.loads(sys.argv[sys.argv.index("--") + 1])
traced = json.load(open(args["json"]))
look = traced["look"]


def blender(v):
    # weir's y up to Blender's z up: (x, y, z) -> (x, -z, y), a rotation (the winding is kept).
    return (v[0], -v[2], v[1])


for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene


def diffuse_material(name):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Roughness"].default_value = 0.0  # Lambertian
    material.node_tree.links.new(bsdf.outputs["BSDF"],
                                 nodes["Material Output"].inputs["Surface"])
    return material, bsdf


def add_object(name, vertices, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)
    return obj


# The water: weir's traced triangles, each corner with its shading normal.
positions, normals = [], []
for line in open(args["obj"]):
    words = line.split()
    if words and words[0] in ("v", "vn"):
        (positions if words[0] == "v" else normals).append(
            blender([float(w) for w in words[1:4]]))
water = bpy.data.materials.new("water")
water.use_nodes = True
water.cycles.homogeneous_volume = True
nodes, links = water.node_tree.nodes, water.node_tree.links
nodes.remove(nodes["Principled BSDF"])
output = nodes["Material Output"]
glass = nodes.new("ShaderNodeBsdfGlass")
if "SHARP" in [item.identifier for item in glass.bl_rna.properties["distribution"].enum_items]:
    glass.distribution = "SHARP"  # Blender 3; later ones are sharp at roughness 0
glass.inputs["Roughness"].default_value = 0.0
glass.inputs["Color"].default_value = (1, 1, 1, 1)
# Shadow rays (the sun sampled from a matte surface) pass straight through, losing the Fresnel
# reflection at each crossing and the absorption inside: weir's sunTransmittance.
fresnel = nodes.new("ShaderNodeFresnel")
passed = nodes.new("ShaderNodeMath")
passed.operation = "SUBTRACT"
passed.inputs[0].default_value = 1.0
links.new(fresnel.outputs["Fac"], passed.inputs[1])
transparent = nodes.new("ShaderNodeBsdfTransparent")
links.new(passed.outputs["Value"], transparent.inputs["Color"])
light_path = nodes.new("ShaderNodeLightPath")
mix = nodes.new("ShaderNodeMixShader")
links.new(light_path.outputs["Is Shadow Ray"], mix.inputs["Fac"])
links.new(glass.outputs["BSDF"], mix.inputs[1])
links.new(transparent.outputs["BSDF"], mix.inputs[2])
links.new(mix.outputs["Shader"], output.inputs["Surface"])
# Beer-Lambert: Cycles absorbs (1 - colour) x density per metre.
absorption = nodes.new("ShaderNodeVolumeAbsorption")
density = max(look["absorption"])
absorption.inputs["Density"].default_value = density
absorption.inputs["Color"].default_value = (*[1 - a / density for a in look["absorption"]], 1)
links.new(absorption.outputs["Volume"], output.inputs["Volume"])
water_object = add_object("water", positions,
                          [(k, k + 1, k + 2) for k in range(0, len(positions), 3)], water)
mesh = water_object.data
for polygon in mesh.polygons:
    polygon.use_smooth = True
if hasattr(mesh, "use_auto_smooth"):  # custom normals need it before Blender 4.1
    mesh.use_auto_smooth = True
    mesh.auto_smooth_angle = math.pi
mesh.normals_split_custom_set([normals[loop.vertex_index] for loop in mesh.loops])

# The floor: weir's checker in the container, grey ground around it (an endless plane: 40 km).
lo, hi = traced["containerLo"], traced["containerHi"]
floor_material, floor_bsdf = diffuse_material("floor")
nodes, links = floor_material.node_tree.nodes, floor_material.node_tree.links


def math_node(operation, a, b=None):
    # A Math node of the tree being built (the global `nodes` and `links` at the call).
    node = nodes.new("ShaderNodeMath")
    node.operation = operation
    for k, value in enumerate((a, b)):
        if value is None:
            continue
        if isinstance(value, (int, float)):
            node.inputs[k].default_value = value
        else:
            links.new(value, node.inputs[k])
    return node.outputs["Value"]


def mix_colour(fac, colour0, colour1):
    node = nodes.new("ShaderNodeMixRGB")
    links.new(fac, node.inputs["Fac"])
    for k, colour in ((1, colour0), (2, colour1)):
        if isinstance(colour, list):
            node.inputs[k].default_value = (*colour, 1)
        else:
            links.new(colour, node.inputs[k])
    return node.outputs["Color"]


position = nodes.new("ShaderNodeSeparateXYZ")
links.new(nodes.new("ShaderNodeNewGeometry").outputs["Position"], position.inputs["Vector"])
x = position.outputs["X"]
z = math_node("MULTIPLY", position.outputs["Y"], -1.0)  # weir's z
size = look["checkerSize"]
squares = math_node("ADD", math_node("FLOOR", math_node("DIVIDE", x, size)),
                    math_node("FLOOR", math_node("DIVIDE", z, size)))
dark = math_node("GREATER_THAN", math_node("ABSOLUTE", math_node("MODULO", squares, 2.0)), 0.5)
inside = math_node("MULTIPLY",
                   math_node("MULTIPLY", math_node("GREATER_THAN", x, lo[0]),
                             math_node("LESS_THAN", x, hi[0])),
                   math_node("MULTIPLY", math_node("GREATER_THAN", z, lo[2]),
                             math_node("LESS_THAN", z, hi[2])))
checker = mix_colour(dark, look["floorLight"], look["floorDark"])
links.new(mix_colour(inside, look["groundAlbedo"], checker), floor_bsdf.inputs["Color"])
far = 2.0e4
add_object("floor", [(-far, -far, lo[1]), (far, -far, lo[1]), (far, far, lo[1]),
                     (-far, far, lo[1])], [(0, 1, 2, 3)], floor_material)

# The side walls weir keeps (those the camera sees from inside).
wall_material, wall_bsdf = diffuse_material("wall")
wall_bsdf.inputs["Color"].default_value = (*look["wallAlbedo"], 1)
for axis, side in traced["walls"]:
    across = 2 - axis
    corners = []
    for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
        p = [0.0, 0.0, 0.0]
        p[axis] = (hi if side else lo)[axis]
        p[1] = (lo, hi)[a][1]
        p[across] = (lo, hi)[b][across]
        corners.append(blender(p))
    add_object(f"wall {axis} {side}", corners, [(0, 1, 2, 3)], wall_material)

# The sky: weir's own, as the equirectangular image it wrote (without the sun's disc).
world = bpy.data.worlds.new("weir sky")
scene.world = world
world.use_nodes = True
nodes, links = world.node_tree.nodes, world.node_tree.links
environment = nodes.new("ShaderNodeTexEnvironment")
environment.image = bpy.data.images.load(args["sky"])
environment.interpolation = "Linear"
world.cycles.sampling_method = "MANUAL"
world.cycles.sample_map_resolution = 1024

# The sun as weir has it: matte surfaces sample its disc directly (a Sun lamp of weir's angular
# diameter and irradiance, sampled only so: no multiple importance sampling), and paths that meet
# nothing but the water from the camera on see the disc (drawn into the world). weir leaves the
# disc out of paths that bounced off a matte surface before (no caustics of the sun): a lamp
# cannot tell those rays apart, the world's shader can (it sees the kind of ray that meets it;
# when Cycles samples the world from a surface it sees none, and draws no disc).
sun = bpy.data.lights.new("sun", "SUN")
irradiance = look["sunIrradiance"]
sun.energy = max(irradiance)
sun.color = [e / sun.energy for e in irradiance]
sun.angle = 2 * look["sunAngularRadius"]
sun.cycles.use_multiple_importance_sampling = False
sun_object = bpy.data.objects.new("sun", sun)
sun_object.rotation_mode = "QUATERNION"
sun_object.rotation_quaternion = mathutils.Vector(
    blender(look["sunDirection"])).to_track_quat("Z", "Y")
scene.collection.objects.link(sun_object)
direction = nodes.new("ShaderNodeNewGeometry").outputs["Position"]  # the ray's, in the world
towards_sun = nodes.new("ShaderNodeVectorMath")
towards_sun.operation = "DOT_PRODUCT"
links.new(direction, towards_sun.inputs[0])
towards_sun.inputs[1].default_value = blender(look["sunDirection"])
in_disc = math_node("GREATER_THAN", towards_sun.outputs["Value"],
                    math.cos(look["sunAngularRadius"]))
path = nodes.new("ShaderNodeLightPath")
seen = path.outputs["Is Camera Ray"]
for kind in ("Is Glossy Ray", "Is Transmission Ray", "Is Singular Ray"):
    seen = math_node("MAXIMUM", seen, path.outputs[kind])
no_matte = math_node("LESS_THAN", path.outputs["Diffuse Depth"], 0.5)
disc = nodes.new("ShaderNodeVectorMath")
disc.operation = "SCALE"
disc.inputs[0].default_value = look["sunDiscRadiance"]
disc_on = nodes.new("ShaderNodeValue")  # 0 for the variant that leaves the sun to the lamp
links.new(math_node("MULTIPLY", math_node("MULTIPLY", in_disc, disc_on.outputs["Value"]),
                    math_node("MULTIPLY", seen, no_matte)), disc.inputs["Scale"])
sky = nodes.new("ShaderNodeVectorMath")
sky.operation = "ADD"
links.new(environment.outputs["Color"], sky.inputs[0])
links.new(disc.outputs["Vector"], sky.inputs[1])
links.new(sky.outputs["Vector"], nodes["Background"].inputs["Color"])

# weir's pinhole camera: eye, right, up, forward; vertical field of view; the image's aspect.
camera = traced["camera"]
camera_data = bpy.data.cameras.new("camera")
camera_data.sensor_fit = "VERTICAL"
camera_data.clip_start, camera_data.clip_end = 1e-3, 1e5
camera_object = bpy.data.objects.new("camera", camera_data)
scene.collection.objects.link(camera_object)
scene.camera = camera_object
columns = [blender(camera["right"]), blender(camera["up"]),
           [-c for c in blender(camera["forward"])]]
turn = mathutils.Matrix([[columns[j][i] for j in range(3)] for i in range(3)])
camera_object.matrix_world = mathutils.Matrix.Translation(blender(camera["eye"])) @ \
    turn.to_4x4()

render = scene.render
render.engine = "CYCLES"
render.resolution_x, render.resolution_y = traced["width"], traced["height"]
render.resolution_percentage = 100
render.threads_mode = "FIXED"
render.threads = args["threads"]
cycles = scene.cycles
cycles.device = "CPU"
cycles.samples = args["samples"]
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.seed = 1
cycles.pixel_filter_type = "BOX"  # weir: a uniform point in the pixel
cycles.filter_width = 1.0
cycles.max_bounces = look["maxSpecularBounces"] + look["maxDiffuseBounces"]
cycles.diffuse_bounces = look["maxDiffuseBounces"]
cycles.glossy_bounces = look["maxSpecularBounces"]
cycles.transmission_bounces = look["maxSpecularBounces"]
cycles.transparent_max_bounces = 64
cycles.volume_bounces = 0
cycles.caustics_reflective = cycles.caustics_refractive = True
cycles.blur_glossy = 0.0
cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
cycles.light_sampling_threshold = 0.0
scene.view_settings.view_transform = "Standard"
render.image_settings.file_format = "OPEN_EXR"
render.image_settings.color_depth = "32"

for variant in args["variants"]:
    for node in (glass, fresnel):
        node.inputs["IOR"].default_value = variant.get("ior", look["refractiveIndex"])
    camera_data.angle_y = 2 * math.atan(camera["tanHalfFovY"] * variant.get("fov", 1.0))
    absorption.inputs["Density"].default_value = density * variant.get("absorption", 1.0)
    # Cycles' own sun: a lamp any ray may meet (caustics of the sun), no disc in the world.
    sun.cycles.use_multiple_importance_sampling = variant.get("lamp_sun", False)
    disc_on.outputs["Value"].default_value = 0.0 if variant.get("lamp_sun", False) else 1.0
    exr = args["out"] + "/" + variant["name"] + ".exr"
    render.filepath = exr
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(exr, check_existing=False)
    width, height = image.size
    rgba = array.array("f", image.pixels[:])
    rows = []
    for row in range(height - 1, -1, -1):  # Blender's rows run from the bottom
        for col in range(width):
            k = 4 * (row * width + col)
            rows.extend(rgba[k:k + 3])
    with open(args["out"] + "/" + variant["name"] + ".f32", "wb") as f:
        array.array("f", rows).tofile(f)
"""


def read_pfm(path):
    """A little-endian RGB PFM as (height, width, 3) float64, rows from the top."""
    data = pathlib.Path(path).read_bytes()
    kind, size, scale, pixels = data.split(b"\n", 3)
    assert kind == b"PF" and float(scale) < 0, "weir writes little-endian RGB PFM"
    width, height = map(int, size.split())
    image = np.frombuffer(pixels, dtype="<f4", count=width * height * 3)
    return image.reshape(height, width, 3)[::-1].astype(np.float64)


def read_raw(path, width, height):
    """The driver's raw float RGB, rows from the top."""
    image = np.fromfile(path, dtype="<f4", count=width * height * 3)
    return image.reshape(height, width, 3).astype(np.float64)


def tone_map(radiance, exposure):
    """weir's toneMapToSrgb8 in NumPy: exposure, Narkowicz's ACES fit, sRGB, 8-bit levels
    (kept as floats: rounded as weir rounds)."""
    x = np.maximum(0.0, radiance * exposure)
    filmic = np.clip((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    encoded = np.where(filmic <= 0.0031308, 12.92 * filmic,
                       1.055 * np.power(filmic, 1 / 2.4) - 0.055)
    return np.floor(np.clip(encoded, 0.0, 1.0) * 255.0 + 0.5)


def blurred(image, sigma=1.0):
    """A separable Gaussian blur (edges clamped), per channel."""
    radius = int(np.ceil(3 * sigma))
    offsets = np.arange(-radius, radius + 1)
    weights = np.exp(-0.5 * (offsets / sigma) ** 2)
    weights /= weights.sum()
    for axis in (0, 1):
        n = image.shape[axis]
        image = sum(w * np.take(image, np.clip(np.arange(n) + o, 0, n - 1), axis=axis)
                    for o, w in zip(offsets, weights))
    return image


def ssim(a, b, window=7):
    """The mean structural similarity (Wang et al. 2004) of two single-channel 8-bit images,
    over all window x window squares (uniform weights), with the usual constants."""
    c1, c2 = (0.01 * 255) ** 2, (0.03 * 255) ** 2

    def means(image):
        view = np.lib.stride_tricks.sliding_window_view(image, (window, window))
        return view.mean(axis=(-1, -2))

    mean_a, mean_b = means(a), means(b)
    var_a = means(a * a) - mean_a ** 2
    var_b = means(b * b) - mean_b ** 2
    cov = means(a * b) - mean_a * mean_b
    index = ((2 * mean_a * mean_b + c1) * (2 * cov + c2)) / \
        ((mean_a ** 2 + mean_b ** 2 + c1) * (var_a + var_b + c2))
    return float(index.mean())


def luma(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def compare(image_a, image_b):
    """The metric on two tone-mapped 8-bit images: (mean absolute difference of the blurred
    images in levels, SSIM of their blurred luma, the largest mean absolute difference over the
    TILE x TILE tiles of the blurred images: a difference confined to the water, a small part
    of the picture, shows there)."""
    a, b = blurred(image_a), blurred(image_b)
    difference = np.abs(a - b).mean(axis=2)
    rows, columns = (n // TILE * TILE for n in difference.shape)
    tiles = difference[:rows, :columns].reshape(rows // TILE, TILE, columns // TILE, TILE)
    return (float(difference.mean()), ssim(luma(a), luma(b)),
            float(tiles.mean(axis=(1, 3)).max()))


def passes(metric):
    mean_difference, similarity, worst_tile = metric
    return (mean_difference <= MAX_MEAN_DIFFERENCE and similarity >= MIN_SSIM
            and worst_tile <= MAX_WORST_TILE)


def side_by_side(images, scale=3):
    """8-bit images in a row, each pixel a scale x scale square, as floats in 0..1."""
    row = np.concatenate(images, axis=1) / 255.0
    return np.kron(row, np.ones((scale, scale, 1)))


@pytest.fixture(scope="module")
def traced(cli, tmp_path_factory):
    """A 3000-particle dam break to frame 12, its surface (`weir mesh`), and the frame path
    traced by weir at 256 and 512 paths per pixel with what was traced exported."""
    out = tmp_path_factory.mktemp("water-cycles")
    run = out / "run"
    cli("run", "dam_break", "--backend", "cpu", "--quiet", "--particles", 3000, "--frames", FRAME,
        "--out", run)
    cli("mesh", run, "--frame", FRAME, "--backend", "cpu", "--format", "obj", "--quiet")
    for paths in (WEIR_PATHS // 2, WEIR_PATHS):
        cli("render", run, "--frame", FRAME, "--look", "water", "--backend", "cpu", "--width",
            WIDTH, "--height", HEIGHT, "--samples", paths, *CAMERA, "--out", out / f"weir{paths}",
            "--export-water", out / f"export{paths}", "--quiet")
    return out


@pytest.fixture(scope="module")
def cycles(traced):
    """Cycles' linear images of the traced scene and of the wrong ones, by name."""
    export = traced / f"export{WEIR_PATHS}"
    out = traced / "cycles"
    out.mkdir()
    driver = out / "driver.py"
    driver.write_text(DRIVER)
    stem = export / f"frame_{FRAME:05d}"
    args = {"json": f"{stem}.json", "obj": f"{stem}_water.obj", "sky": str(export / "sky.hdr"),
            "out": str(out), "threads": 2, "samples": CYCLES_SAMPLES,
            "variants": [RIGHT, *WRONG]}
    done = subprocess.run(["nice", BLENDER, "-b", "--factory-startup", "-t", "2",
                           "--python-exit-code", "1", "--python", str(driver), "--",
                           json.dumps(args)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, \
        f"blender exited {done.returncode}:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return {v["name"]: read_raw(out / f"{v['name']}.f32", WIDTH, HEIGHT) for v in [RIGHT, *WRONG]}


def obj_lines(path):
    return pathlib.Path(path).read_text().splitlines()


def obj_points(lines):
    """The `v` positions of an OBJ's lines, (n, 3)."""
    return np.array([[float(w) for w in line.split()[1:4]] for line in lines
                     if line.startswith("v ")])


def weir_image(traced, paths):
    return read_pfm(traced / f"export{paths}" / f"frame_{FRAME:05d}.pfm")


def exposure(traced):
    stem = traced / f"export{WEIR_PATHS}" / f"frame_{FRAME:05d}"
    return json.loads(stem.with_suffix(".json").read_text())["look"]["exposure"]


def test_the_tone_map_here_is_weirs(traced):
    """The NumPy tone map turns weir's linear image into the PNG weir wrote (in double
    precision here, in float there: a value at a rounding boundary may differ by one level)."""
    import matplotlib.image

    png = matplotlib.image.imread(str(traced / f"weir{WEIR_PATHS}" / f"frame_{FRAME:05d}.png"))
    mapped = tone_map(weir_image(traced, WEIR_PATHS), exposure(traced))
    difference = np.abs(np.round(png[..., :3] * 255) - mapped)
    assert difference.max() <= 1 and np.mean(difference > 0) < 1e-3


def test_the_exported_water_is_the_surface_weir_mesh_wrote(traced):
    """weir traced the surface of `weir mesh`, less the faces lying on the floor and walls."""
    stem = traced / f"export{WEIR_PATHS}" / f"frame_{FRAME:05d}"
    scene = json.loads(stem.with_suffix(".json").read_text())
    mesh = obj_lines(traced / "run" / "mesh" / f"surface_{FRAME:05d}.obj")
    triangles = [line for line in mesh if line.startswith("f ")]
    kept, left_out = scene["waterTriangles"], scene["contactTrianglesLeftOut"]
    assert kept > 1000 and left_out > 0
    # Degenerate faces (no area) are in neither count.
    assert 0.999 * len(triangles) <= kept + left_out <= len(triangles)
    traced_points = obj_points(obj_lines(f"{stem}_water.obj"))
    assert len(traced_points) == 3 * kept
    mesh_points = obj_points(mesh)
    on_grid = {tuple(p) for p in np.round(mesh_points, 4)}
    found = np.mean([tuple(p) in on_grid for p in np.round(traced_points, 4)])
    assert found > 0.99, found


def test_cycles_renders_the_picture_weir_traces(traced, cycles, tmp_path):
    """The metric of weir's image against Cycles' stays within the thresholds, which lie well
    above the noise floor (two weir images of independent paths)."""
    scale = exposure(traced)
    full = weir_image(traced, WEIR_PATHS)
    first_half = weir_image(traced, WEIR_PATHS // 2)
    second_half = 2 * full - first_half  # paths 256..511 alone
    weir = tone_map(full, scale)
    blender = tone_map(cycles[RIGHT["name"]], scale)
    noise = compare(tone_map(first_half, scale), tone_map(second_half, scale))
    measured = compare(weir, blender)
    print("noise floor: {:.3f} levels, SSIM {:.4f}, worst tile {:.2f} levels".format(*noise))
    print("weir against Cycles: {:.3f} levels, SSIM {:.4f}, worst tile {:.2f} levels"
          .format(*measured))
    assert noise[0] < 0.5 * MAX_MEAN_DIFFERENCE and noise[1] > MIN_SSIM
    assert noise[2] < 0.5 * MAX_WORST_TILE
    difference = np.abs(blurred(weir) - blurred(blender))
    import matplotlib.image

    for folder in filter(None, (tmp_path, PICTURES and pathlib.Path(PICTURES))):
        matplotlib.image.imsave(folder / "water_look_cycles.png",
                                side_by_side([weir, blender, np.clip(8 * difference, 0, 255)]))
    for name, image in (("weir", weir), ("cycles", blender), ("difference", 8 * difference)):
        matplotlib.image.imsave(tmp_path / f"{name}.png", np.clip(image, 0, 255) / 255.0)
    assert passes(measured), measured


@pytest.mark.parametrize("variant", [v["name"] for v in WRONG])
def test_a_wrong_scene_in_cycles_fails_the_metric(traced, cycles, variant):
    """The metric tells water from glass, a field of view 3 % off, half the absorption and the
    sun's caustics that weir leaves out: each fails it."""
    scale = exposure(traced)
    measured = compare(tone_map(weir_image(traced, WEIR_PATHS), scale),
                       tone_map(cycles[variant], scale))
    print("{}: {:.3f} levels, SSIM {:.4f}, worst tile {:.2f} levels".format(variant, *measured))
    assert not passes(measured), measured


def test_export_water_needs_the_water_look(cli, traced, tmp_path):
    done = cli("render", traced / "run", "--frame", FRAME, "--export-water", tmp_path / "export",
               "--quiet", check=False)
    assert done.returncode == 2 and "needs --look water" in done.stderr
    assert not (tmp_path / "export").exists()
