"""weir_blender: a weir run folder in Blender (3.4 or later), ready for Cycles with motion blur.

Debian 12's Blender (3.4.1) is built without USD and Alembic import, so this reads the files of a
run that Blender can take without them (docs/pipeline.md, "Blender"):

  mesh/surface_NNNNN.ply  the fluid's surface (weir run --mesh --mesh-format ply, or weir mesh),
                          given a per-vertex `velocity` attribute that Cycles motion-blurs by:
                          each vertex the mean velocity of the particles within 2 d, weighted by
                          (1 - r^2/R^2)^3, as weir's USD stage has it
  frame_NNNNN.ply / .csv  the particles: points with `velocity`, `id`, `density`, `pressure`,
                          drawn as spheres of diameter d (a Geometry Nodes modifier)
  *_NNNNN.vdb             an OpenVDB volume (mesh/surface_NNNNN.vdb, else the frame's .vdb): the
                          grids `surface` (level set) and `velocity` (the volume's motion blur)

The objects sit under an empty "weir" that turns weir's y-up metres into Blender's z-up. A frame
handler loads the surface and particles of each frame as the timeline moves (the volume is a
Blender volume sequence), so the run plays and renders as an animation.

As an add-on: Edit > Preferences > Add-ons > Install... (this file), enable "Import-Export: weir
run", then File > Import > weir run (frames.json). From a shell, without installing it:

  blender -b --python tools/blender/weir_blender.py -- RUN_DIR [--frame N] [--render OUT.png]
          [--width 640 --height 360 --samples 32] [--no-motion-blur] [--shutter 0.5]
          [--particles] [--volume] [--save OUT.blend]

renders frame N (default: the run's last) in Cycles on the CPU, with a camera, light and floor
placed from the run's container.
"""

import json
import math
import os
import struct
import sys

import bpy
import mathutils
from bpy.app.handlers import persistent
from mathutils.kdtree import KDTree

bl_info = {
    "name": "weir run",
    "author": "weir",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > weir run (frames.json)",
    "description": "A weir SPH run: surface meshes with velocities, particles, OpenVDB volume",
    "category": "Import-Export",
}

# --- Reading weir's files -----------------------------------------------------------------------

_PLY_TYPES = {"float": "f", "float32": "f", "double": "d", "float64": "d", "int": "i",
              "int32": "i", "uint": "I", "uint32": "I", "uchar": "B", "uint8": "B", "char": "b",
              "int8": "b", "short": "h", "int16": "h", "ushort": "H", "uint16": "H"}


def read_ply(path):
    """A binary little-endian PLY as weir writes it: ({property: values} of the vertices, a flat
    list of triangle indices). Faces must be triangles (weir's are)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        raise ValueError(f"{path}: not a PLY file")
    elements = []  # [name, count, [(property, type)] or ("list", count type, item type)]
    for line in data[:end].decode("ascii").splitlines():
        words = line.split()
        if words[:1] == ["format"] and words[1] != "binary_little_endian":
            raise ValueError(f"{path}: PLY format {words[1]} (weir writes binary_little_endian)")
        if words[:1] == ["element"]:
            elements.append([words[1], int(words[2]), []])
        elif words[:1] == ["property"] and words[1] == "list":
            elements[-1][2] = ("list", _PLY_TYPES[words[2]], _PLY_TYPES[words[3]])
        elif words[:1] == ["property"]:
            elements[-1][2].append((words[2], _PLY_TYPES[words[1]]))
    offset = end + len("end_header\n")
    vertices, triangles = {}, []
    try:
        for name, count, properties in elements:
            if properties and properties[0] == "list":
                _, count_type, item_type = properties
                record = count_type + 3 * item_type
                values = struct.unpack_from("<" + record * count, data, offset)
                if any(n != 3 for n in values[0::4]):
                    raise ValueError(f"{path}: faces that are not triangles")
                triangles = [v for i, v in enumerate(values) if i % 4]
            else:
                record = "".join(t for _, t in properties)
                values = struct.unpack_from("<" + record * count, data, offset)
                if name == "vertex":
                    n = len(properties)
                    vertices = {p: values[k::n] for k, (p, _) in enumerate(properties)}
            offset += struct.calcsize("<" + record) * count
    except struct.error as error:
        raise ValueError(f"{path}: truncated or damaged PLY ({error})") from None
    return vertices, triangles


def read_csv(path):
    """A weir CSV frame: {column: values}."""
    with open(path) as f:
        header = f.readline().strip().split(",")
        columns = list(zip(*(map(float, line.split(",")) for line in f if line.strip())))
    return {name: columns[k] if columns else () for k, name in enumerate(header)}


class Run:
    """A weir run folder: its frames.json, and its files by frame number."""

    def __init__(self, folder):
        self.folder = os.path.abspath(folder)
        index_path = os.path.join(self.folder, "frames.json")
        if not os.path.isfile(index_path):
            raise FileNotFoundError(f"{index_path}: no such file (is '{folder}' the output "
                                    "folder of weir run?)")
        with open(index_path) as f:
            self.index = json.load(f)
        self.numbers = [entry["index"] for entry in self.index["frames"]]
        self.spacing = float(self.index.get("spacing") or 0.02)
        definition = self.index.get("scene", {}).get("definition") or {}
        self.container = definition.get("container")
        self.fps = float(definition.get("time", {}).get("frameRate") or 30)

    def file(self, pattern, number):
        """The existing file among pattern (a list of names with {n:05d}) for this frame."""
        for name in pattern:
            path = os.path.join(self.folder, name.format(n=number))
            if os.path.isfile(path):
                return path
        return None

    def surface_file(self, number):
        return self.file(["mesh/surface_{n:05d}.ply"], number)

    def particle_file(self, number):
        return self.file(["frame_{n:05d}.ply", "frame_{n:05d}.csv"], number)

    def volume_file(self, number):
        return self.file(["mesh/surface_{n:05d}.vdb", "frame_{n:05d}.vdb"], number)

    def particles(self, number):
        path = self.particle_file(number)
        if path is None:
            return None
        return read_ply(path)[0] if path.endswith(".ply") else read_csv(path)


# --- Building Blender data ----------------------------------------------------------------------

def _vectors(table, names):
    return list(zip(*(table[n] for n in names)))


def surface_velocities(positions, particles, spacing):
    """Each vertex's velocity: the particles within R = 2 d, weighted by (1 - r^2/R^2)^3 (weir's
    USD surface velocities); the nearest particle's where none is that close."""
    centres = _vectors(particles, "xyz")
    velocities = _vectors(particles, ("vx", "vy", "vz"))
    tree = KDTree(len(centres))
    for i, c in enumerate(centres):
        tree.insert(c, i)
    tree.balance()
    radius = 2.0 * spacing
    out = []
    for p in positions:
        total, vx, vy, vz = 0.0, 0.0, 0.0, 0.0
        for _, i, r in tree.find_range(p, radius):
            w = (1.0 - (r * r) / (radius * radius)) ** 3
            v = velocities[i]
            total += w
            vx += w * v[0]
            vy += w * v[1]
            vz += w * v[2]
        if total > 0.0:
            out.append((vx / total, vy / total, vz / total))
        else:
            out.append(velocities[tree.find(p)[1]] if centres else (0.0, 0.0, 0.0))
    return out


def _flat(vectors):
    return [c for v in vectors for c in v]


def surface_mesh(run, number, name="weir surface"):
    """The frame's surface as a Blender mesh with a point attribute `velocity` (m/s), or None."""
    path = run.surface_file(number)
    if path is None:
        return None
    vertices, triangles = read_ply(path)
    positions = _vectors(vertices, "xyz")
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(positions))
    mesh.vertices.foreach_set("co", _flat(positions))
    count = len(triangles) // 3
    mesh.loops.add(len(triangles))
    mesh.loops.foreach_set("vertex_index", triangles)
    mesh.polygons.add(count)
    mesh.polygons.foreach_set("loop_start", range(0, 3 * count, 3))
    mesh.polygons.foreach_set("loop_total", [3] * count)
    mesh.polygons.foreach_set("use_smooth", [True] * count)
    mesh.update()
    if "vx" in vertices:
        velocity = _vectors(vertices, ("vx", "vy", "vz"))
    else:
        particles = run.particles(number)
        velocity = (surface_velocities(positions, particles, run.spacing) if particles
                    else [(0.0, 0.0, 0.0)] * len(positions))
    mesh.attributes.new("velocity", "FLOAT_VECTOR", "POINT").data.foreach_set(
        "vector", _flat(velocity))
    mesh["weir_frame"] = number
    return mesh


def particle_mesh(run, number, name="weir particles"):
    """The frame's particles as a mesh of vertices with `velocity`, `id`, `density`, `pressure`."""
    table = run.particles(number)
    if table is None:
        return None
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(table["x"]))
    mesh.vertices.foreach_set("co", _flat(_vectors(table, "xyz")))
    mesh.attributes.new("velocity", "FLOAT_VECTOR", "POINT").data.foreach_set(
        "vector", _flat(_vectors(table, ("vx", "vy", "vz"))))
    if "id" in table:
        mesh.attributes.new("id", "INT", "POINT").data.foreach_set(
            "value", [int(i) for i in table["id"]])
    for field in ("density", "pressure"):
        if field in table:
            mesh.attributes.new(field, "FLOAT", "POINT").data.foreach_set("value", table[field])
    mesh.update()
    mesh["weir_frame"] = number
    return mesh


def _material(name, color, transmission, roughness):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = 1.33
    return material


def _points_modifier(obj, radius, material):
    """Geometry Nodes: the mesh's vertices become a point cloud of spheres (Cycles renders them,
    and motion-blurs them by their `velocity`)."""
    group = bpy.data.node_groups.new("weir points", "GeometryNodeTree")
    group.inputs.new("NodeSocketGeometry", "Geometry")
    group.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = group.nodes, group.links
    into, out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    points = nodes.new("GeometryNodeMeshToPoints")
    points.inputs["Radius"].default_value = radius
    paint = nodes.new("GeometryNodeSetMaterial")
    paint.inputs["Material"].default_value = material
    links.new(into.outputs[0], points.inputs["Mesh"])
    links.new(points.outputs[0], paint.inputs["Geometry"])
    links.new(paint.outputs[0], out.inputs[0])
    obj.modifiers.new("weir points", "NODES").node_group = group


def _sequence_volume(run, name="weir volume"):
    """A Blender volume sequence over the run's .vdb files (scene frame N reads file N)."""
    numbers = [n for n in run.numbers if run.volume_file(n)]
    if not numbers:
        return None
    volume = bpy.data.volumes.new(name)
    volume.filepath = run.volume_file(numbers[0])
    volume.is_sequence = len(numbers) > 1
    volume.frame_start = numbers[0]
    volume.frame_duration = len(numbers)
    volume.frame_offset = numbers[0] - 1
    volume.sequence_mode = "CLIP"
    volume.grids.load()
    volume.velocity_grid = "velocity"  # m/s: Cycles motion-blurs the volume by it
    volume.velocity_unit = "SECOND"
    return volume


def volume_surface(volume_obj, name="weir surface (vdb)"):
    """A mesh object that draws the volume's level set `surface` (a Volume to Mesh modifier): the
    fluid's surface from VDB files alone; it has no velocities, so it is not motion-blurred."""
    obj = bpy.data.objects.new(name, bpy.data.meshes.new(name))
    obj.parent = volume_obj.parent
    for collection in volume_obj.users_collection:
        collection.objects.link(obj)
    to_mesh = obj.modifiers.new("weir surface", "VOLUME_TO_MESH")
    to_mesh.object = volume_obj
    to_mesh.grid_name = "surface"
    to_mesh.threshold = 0.0  # the level set's zero: weir's surface
    to_mesh.resolution_mode = "GRID"
    to_mesh.use_smooth_shade = True
    obj.data.materials.append(bpy.data.materials.get("weir water") or _water())
    return obj


def _water():
    return _material("weir water", (0.55, 0.75, 0.95), 1.0, 0.03)


def _update(obj, build, number):
    if obj.data.get("weir_frame") == number:
        return
    run = Run(obj["weir_run"])
    mesh = build(run, number, obj.data.name)
    if mesh is None:
        return
    old, name = obj.data, obj.data.name
    obj.data = mesh
    for material in old.materials:
        mesh.materials.append(material)
    if old.users == 0:
        bpy.data.meshes.remove(old)
        mesh.name = name


@persistent
def on_frame_change(scene, depsgraph=None):
    """Loads each weir object's mesh for the scene's frame (frame number = weir's number)."""
    for obj in scene.objects:
        kind = obj.get("weir_kind")
        if kind == "surface":
            _update(obj, surface_mesh, scene.frame_current)
        elif kind == "particles":
            _update(obj, particle_mesh, scene.frame_current)


def _watch_frames():
    handlers = bpy.app.handlers.frame_change_pre
    if not any(getattr(h, "__name__", "") == "on_frame_change" for h in handlers):
        handlers.append(on_frame_change)


def load_run(folder, frame=None, scene=None, surface=True, particles=True, volume=True):
    """Adds a run's objects to the scene at its frame `frame` (default: the last), under an empty
    "weir"; sets the scene's frame range and rate. Returns {"root", "surface", "particles",
    "volume", "volume surface"} (each None where the run has no such files; the volume's surface
    is made only where the run has no surface meshes)."""
    scene = scene or bpy.context.scene
    run = Run(folder)
    number = run.numbers[-1] if frame is None else int(frame)
    if number not in run.numbers:
        raise ValueError(f"{run.folder} has no frame {number}: its frames are "
                         f"{run.numbers[0]}..{run.numbers[-1]}")
    scene.frame_start, scene.frame_end = run.numbers[0], run.numbers[-1]
    scene.render.fps, scene.render.fps_base = round(run.fps), round(run.fps) / run.fps
    scene.frame_set(number)
    root = bpy.data.objects.new("weir", None)
    root.rotation_euler = (math.pi / 2, 0.0, 0.0)  # weir's +y up is Blender's +z up
    root["weir_run"] = run.folder
    scene.collection.objects.link(root)
    made = {"root": root, "surface": None, "particles": None, "volume": None,
            "volume surface": None}

    def add(name, data, kind):
        obj = bpy.data.objects.new(name, data)
        obj.parent = root
        obj["weir_run"], obj["weir_kind"] = run.folder, kind
        scene.collection.objects.link(obj)
        made[kind] = obj
        return obj

    if surface and (mesh := surface_mesh(run, number)) is not None:
        mesh.materials.append(_water())
        add("weir surface", mesh, "surface")
    if particles and (mesh := particle_mesh(run, number)) is not None:
        obj = add("weir particles", mesh, "particles")
        _points_modifier(obj, 0.5 * run.spacing,
                         _material("weir particles", (0.1, 0.35, 0.8), 0.0, 0.4))
    if volume and (data := _sequence_volume(run)) is not None:
        obj = add("weir volume", data, "volume")
        # Blender 3.4 draws and meshes an OpenVDB grid half a voxel towards +x, +y, +z of where
        # OpenVDB puts it (measured: a level-set sphere of radius 1 about the origin, voxel 0.1,
        # renders and meshes over -0.95..1.05); the object's offset puts it back.
        grid = data.grids.get("surface") or data.grids[0]
        obj.location = -0.5 * grid.matrix_object.to_3x3() @ mathutils.Vector((1.0, 1.0, 1.0))
        if surface and made["surface"] is None:
            made["volume surface"] = volume_surface(made["volume"])
    _watch_frames()
    return made


# --- A camera, light and floor, and Cycles settings ---------------------------------------------

def _bounds(run, made):
    """The container's corners in Blender's axes (z up), else the loaded objects' bounds."""
    obj = made["surface"] or made["particles"]
    if run.container:
        lo, hi = run.container["min"], run.container["max"]
    elif obj is not None:
        xs = [v.co for v in obj.data.vertices]
        lo = [min(p[a] for p in xs) for a in range(3)]
        hi = [max(p[a] for p in xs) for a in range(3)]
    else:
        lo, hi = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
    return (mathutils.Vector((lo[0], -hi[2], lo[1])), mathutils.Vector((hi[0], -lo[2], hi[1])))


def stage(made, scene=None, width=640, height=360, samples=32, motion_blur=True, shutter=0.5):
    """Camera, sun, floor and Cycles (CPU) settings for rendering the loaded run."""
    scene = scene or bpy.context.scene
    run = Run(made["root"]["weir_run"])
    lo, hi = _bounds(run, made)
    centre, size = (lo + hi) / 2, (hi - lo).length
    # Aimed at the fluid of the loaded frame (the container's centre is often above it), from a
    # distance set by the container.
    target = centre
    fluid = made["surface"] or made["particles"]
    if fluid is not None and len(fluid.data.vertices):
        bpy.context.view_layer.update()
        corners = [fluid.matrix_world @ mathutils.Vector(c) for c in fluid.bound_box]
        target = sum(corners, mathutils.Vector()) / len(corners)
    camera = bpy.data.objects.new("weir camera", bpy.data.cameras.new("weir camera"))
    camera.data.lens = 35
    camera.location = target + mathutils.Vector((0.25, -1.0, 0.55)).normalized() * 1.1 * size
    camera.rotation_euler = (target - camera.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun = bpy.data.objects.new("weir sun", bpy.data.lights.new("weir sun", "SUN"))
    sun.data.energy = 4.0
    sun.rotation_euler = (math.radians(40), math.radians(15), math.radians(30))
    scene.collection.objects.link(sun)
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(centre.x, centre.y, lo.z))
    floor = bpy.context.active_object
    floor.name = "weir floor"
    floor.scale = (3 * (hi.x - lo.x), 3 * (hi.y - lo.y), 1.0)
    floor.data.materials.append(_material("weir floor", (0.5, 0.5, 0.48), 0.0, 0.6))
    world = scene.world or bpy.data.worlds.new("weir world")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.85, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False  # Debian's build has no denoiser (no OpenImageDenoise)
    # Fewer fireflies through the water at few samples: no caustics, indirect light clamped.
    scene.cycles.caustics_reflective = scene.cycles.caustics_refractive = False
    scene.cycles.sample_clamp_indirect = 10.0
    scene.cycles.blur_glossy = 1.0
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.use_motion_blur = motion_blur
    scene.render.motion_blur_shutter = shutter  # in frames: 0.5 = a 180-degree shutter
    return camera


def main(argv):
    import argparse

    parser = argparse.ArgumentParser(prog="blender -b --python weir_blender.py --",
                                     description="Load a weir run; optionally render a frame.")
    parser.add_argument("run", help="the output folder of weir run (with frames.json)")
    parser.add_argument("--frame", type=int, help="frame number (default: the run's last)")
    parser.add_argument("--render", metavar="PNG", help="render the frame in Cycles to PNG")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--samples", type=int, default=32)
    parser.add_argument("--shutter", type=float, default=0.5, help="in frames (default 0.5)")
    parser.add_argument("--no-motion-blur", action="store_true")
    parser.add_argument("--particles", action="store_true",
                        help="render the particles as spheres (default: the surface only)")
    parser.add_argument("--volume", action="store_true",
                        help="render the OpenVDB volume as well (default: viewport only)")
    parser.add_argument("--save", metavar="BLEND", help="save the scene as a .blend file")
    args = parser.parse_args(argv)
    for obj in list(bpy.data.objects):  # the start-up cube, camera and light
        bpy.data.objects.remove(obj)
    made = load_run(args.run, args.frame)
    if not (made["surface"] or made["volume surface"] or made["particles"]):
        raise ValueError(f"{args.run} has no surface meshes (mesh/surface_*.ply), .vdb files or "
                         "particle frames (.ply, .csv) that Blender can read")
    surfaced = made["surface"] or made["volume surface"]
    for kind, shown in (("particles", args.particles or not surfaced), ("volume", args.volume)):
        if made[kind] is not None:
            made[kind].hide_render = not shown
    stage(made, width=args.width, height=args.height, samples=args.samples,
          motion_blur=not args.no_motion_blur, shutter=args.shutter)
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))
    if args.render:
        bpy.context.scene.render.filepath = os.path.abspath(args.render)
        bpy.ops.render.render(write_still=True)


# --- The add-on: File > Import > weir run -------------------------------------------------------

class ImportWeirRun(bpy.types.Operator):
    """Load a weir run folder: surface meshes with velocities, particles, OpenVDB volume"""

    bl_idname = "import_scene.weir_run"
    bl_label = "Import weir run"
    bl_options = {"REGISTER", "UNDO"}
    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="frames.json", options={"HIDDEN"})
    surface: bpy.props.BoolProperty(name="Surface meshes", default=True)
    particles: bpy.props.BoolProperty(name="Particles", default=True)
    volume: bpy.props.BoolProperty(name="OpenVDB volume", default=True)

    def execute(self, context):
        try:
            load_run(os.path.dirname(self.filepath), None, context.scene, self.surface,
                     self.particles, self.volume)
        except (OSError, ValueError, KeyError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}


def _menu(self, context):
    self.layout.operator(ImportWeirRun.bl_idname, text="weir run (frames.json)")


def register():
    bpy.utils.register_class(ImportWeirRun)
    bpy.types.TOPBAR_MT_file_import.append(_menu)
    _watch_frames()


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu)
    bpy.utils.unregister_class(ImportWeirRun)


if __name__ == "__main__":
    try:
        main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    except (OSError, ValueError, KeyError) as error:
        sys.exit(f"weir_blender: {error}")  # exit status 1 (Blender's own is 0 after an error)
    except Exception:
        import traceback

        traceback.print_exc()
        sys.exit(1)
