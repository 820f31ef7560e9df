# The peer of toonwater's default look in Blender Cycles: the same water meshes, object, camera,
# sun direction and band colours, drawn the way a Blender user draws toon water: a colour ramp
# (constant, three bands) on the light angle L·n, emitted flat, and Freestyle outlines; with
# --see-through, the water's free surface lets toonwater's share of what lies behind show through.
# Camera, sun, colours and band limits are read from a toonwater scene directory (scene.pov of
# `toonwater povgen --up z`), so both renders show the same frames from the same place.
#   blender -b --factory-startup --python bench/peer/cycles_toon.py -- \
#       --scene SCENE_DIR --water 'cache/mesh/fluid_mesh_####.bobj.gz' --scale 1.2 \
#       --translate 0,0,0.3 [--object 'sphere_####.obj'] --frames 14-22 [--see-through] --out DIR
# Writes DIR/frame_NNNN.png, each renamed into place complete. Exits 1 on any error (Blender's
# --python-exit-code 1) with one line naming the file.
import argparse
import gzip
import math
import os
import re
import struct
import sys

import bpy
from mathutils import Vector

SAMPLES = 4
LINE_WIDTH_PX = 2.0


class PeerError(Exception):
    pass


# --- reading toonwater's scene -------------------------------------------------------------

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
VECTOR = r"<\s*(%s)\s*,\s*(%s)\s*,\s*(%s)\s*>" % (NUMBER, NUMBER, NUMBER)


def world_from_pov(v):
    """POV-Ray's y-up point of a `povgen --up z` scene in Blender's z-up world: (x, z, y)."""
    return Vector((v[0], v[2], v[1]))


def find(pattern, text, what, path):
    match = re.search(pattern, text, re.S)
    if match is None:
        raise PeerError("%s: no %s found (a scene of `toonwater povgen --up z`?)" % (path, what))
    return match


def vector(match, first=1):
    return tuple(float(match.group(first + i)) for i in range(3))


def read_scene(scene_dir):
    """Camera, sun, colours (sRGB) and band limits of a toonwater scene's scene.pov, and the
    image size of its scene.ini."""
    path = os.path.join(scene_dir, "scene.pov")
    try:
        with open(path, encoding="utf-8") as f:
            pov = f.read()
        with open(os.path.join(scene_dir, "scene.ini"), encoding="utf-8") as f:
            ini = f.read()
    except OSError as e:
        raise PeerError("%s: %s" % (e.filename, e.strerror)) from None
    camera = find(r"camera\s*\{(.*?)\}", pov, "camera", path).group(1)
    light = find(r"light_source\s*\{\s*%s[^}]*?parallel\s+point_at\s*%s" % (VECTOR, VECTOR),
                 pov, "parallel light (sun)", path)
    water = find(r"Toon_bands\(\s*srgb\s*%s\s*,\s*srgb\s*%s\s*,\s*srgb\s*%s\s*,\s*(%s)\s*,\s*(%s)"
                 r"\s*,\s*(%s)" % (VECTOR, VECTOR, VECTOR, NUMBER, NUMBER, NUMBER),
                 pov, "water bands", path)
    background = find(r"background\s*\{\s*color\s+srgb\s*%s" % VECTOR, pov, "background", path)
    objects = re.search(r"Toon_object_bands\(\s*srgb\s*%s\s*,\s*(%s)\s*,\s*(%s)\s*\)"
                        % (VECTOR, NUMBER, NUMBER), pov)
    towards_light = (world_from_pov(vector(light, 1)) - world_from_pov(vector(light, 4)))
    scene = {
        "location": world_from_pov(vector(find(r"location\s*%s" % VECTOR, camera,
                                               "camera location", path))),
        "look_at": world_from_pov(vector(find(r"look_at\s*%s" % VECTOR, camera,
                                              "camera look_at", path))),
        "angle": float(find(r"angle\s+(%s)" % NUMBER, camera, "camera angle", path).group(1)),
        "light": towards_light.normalized(),
        "water": {"bright": vector(water, 1), "medium": vector(water, 4),
                  "dark": vector(water, 7), "t_bright": float(water.group(10)),
                  "t_medium": float(water.group(11)), "transmit": float(water.group(12))},
        "background": vector(background),
        "width": int(find(r"(?m)^Width=(\d+)", ini, "Width", path).group(1)),
        "height": int(find(r"(?m)^Height=(\d+)", ini, "Height", path).group(1)),
    }
    if objects is not None:
        color = vector(objects)
        scene["object"] = {"bright": color, "medium": tuple(0.6 * c for c in color),
                           "dark": tuple(0.3 * c for c in color),
                           "t_bright": float(objects.group(4)), "t_medium": float(objects.group(5))}
    return scene


# --- reading meshes ------------------------------------------------------------------------

def read_bobj_gz(path, scale, translate):
    """Mantaflow's mesh cache (gzip, little-endian): int32 nv, nv×3 float32 positions, int32 nn,
    nn×3 float32 normals, int32 nt, nt×3 int32 triangles; world = scale·v + translate."""
    try:
        with gzip.open(path, "rb") as f:
            data = f.read()
        nv = struct.unpack_from("<i", data, 0)[0]
        positions = struct.unpack_from("<%df" % (3 * nv), data, 4)
        offset = 4 + 12 * nv
        nn = struct.unpack_from("<i", data, offset)[0]
        offset += 4 + 12 * nn
        nt = struct.unpack_from("<i", data, offset)[0]
        triangles = struct.unpack_from("<%di" % (3 * nt), data, offset + 4)
    except (OSError, EOFError, struct.error) as e:
        raise PeerError("%s: not a readable Mantaflow mesh cache (%s)" % (path, e)) from None
    if nv < 0 or nt < 0 or (triangles and not 0 <= min(triangles) <= max(triangles) < nv):
        raise PeerError("%s: counts or triangle indices out of range" % path)
    coords = [scale * p + translate[i % 3] for i, p in enumerate(positions)]
    return coords, triangles


def read_obj(path):
    """Positions and triangles of an OBJ of `v x y z` and `f a b c` lines (1-based)."""
    coords, triangles = [], []
    try:
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                fields = line.split()
                if not fields:
                    continue
                if fields[0] == "v":
                    coords.extend(float(x) for x in fields[1:4])
                elif fields[0] == "f":
                    if len(fields) != 4:
                        raise PeerError("%s:%d: only triangles are read" % (path, number))
                    triangles.extend(int(x.split("/")[0]) - 1 for x in fields[1:4])
    except OSError as e:
        raise PeerError("%s: %s" % (path, e.strerror)) from None
    except ValueError:
        raise PeerError("%s: a malformed number" % path) from None
    return coords, triangles


def smooth_mesh(name, coords, triangles):
    """A Blender mesh of triangles, smooth-shaded (the vertex normals give L·n)."""
    mesh = bpy.data.meshes.new(name)
    nt = len(triangles) // 3
    mesh.vertices.add(len(coords) // 3)
    mesh.vertices.foreach_set("co", coords)
    mesh.loops.add(3 * nt)
    mesh.loops.foreach_set("vertex_index", triangles)
    mesh.polygons.add(nt)
    mesh.polygons.foreach_set("loop_start", range(0, 3 * nt, 3))
    mesh.polygons.foreach_set("loop_total", [3] * nt)
    mesh.polygons.foreach_set("use_smooth", [True] * nt)
    mesh.update()
    return mesh


def frame_path(pattern, frame):
    """`####` (any run of #) replaced by the frame number, zero-padded to its length."""
    return re.sub(r"#+", lambda m: "%0*d" % (len(m.group(0)), frame), pattern, count=1)


# --- the Blender scene -----------------------------------------------------------------------

def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def linear_rgba(srgb):
    return tuple(srgb_to_linear(c) for c in srgb) + (1.0,)


def toon_material(name, bands, towards_light, transmit=0.0):
    """Emission of a constant ColorRamp on L·n: dark below t_medium, medium below t_bright,
    bright above, the limits toonwater's scene uses. A share `transmit` of the front faces
    lets what lies behind show through, as toonwater's free surface does; back faces (a closed
    volume's floor and walls seen from inside) are opaque, as toonwater's body is."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    geometry = nodes.new("ShaderNodeNewGeometry")
    light = nodes.new("ShaderNodeCombineXYZ")
    for i, axis in enumerate("XYZ"):
        light.inputs[axis].default_value = towards_light[i]
    dot = nodes.new("ShaderNodeVectorMath")
    dot.operation = 'DOT_PRODUCT'
    to_unit = nodes.new("ShaderNodeMath")  # L·n in [-1, 1] to the ramp's [0, 1]
    to_unit.operation = 'MULTIPLY_ADD'
    to_unit.inputs[1].default_value = 0.5
    to_unit.inputs[2].default_value = 0.5
    ramp = nodes.new("ShaderNodeValToRGB")
    ramp.color_ramp.interpolation = 'CONSTANT'
    elements = ramp.color_ramp.elements
    elements[0].position = 0.0
    elements[0].color = linear_rgba(bands["dark"])
    elements[1].position = 0.5 + 0.5 * bands["t_medium"]
    elements[1].color = linear_rgba(bands["medium"])
    bright = elements.new(0.5 + 0.5 * bands["t_bright"])
    bright.color = linear_rgba(bands["bright"])
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(geometry.outputs["Normal"], dot.inputs[0])
    links.new(light.outputs["Vector"], dot.inputs[1])
    links.new(dot.outputs["Value"], to_unit.inputs[0])
    links.new(to_unit.outputs["Value"], ramp.inputs["Fac"])
    links.new(ramp.outputs["Color"], emission.inputs["Color"])
    if transmit <= 0.0:
        links.new(emission.outputs["Emission"], output.inputs["Surface"])
        return material
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    front_share = nodes.new("ShaderNodeMath")  # transmit · (1 − backfacing)
    front_share.operation = 'MULTIPLY_ADD'
    front_share.inputs[1].default_value = -transmit
    front_share.inputs[2].default_value = transmit
    mix = nodes.new("ShaderNodeMixShader")
    links.new(geometry.outputs["Backfacing"], front_share.inputs[0])
    links.new(front_share.outputs["Value"], mix.inputs["Fac"])
    links.new(emission.outputs["Emission"], mix.inputs[1])
    links.new(transparent.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], output.inputs["Surface"])
    return material


def setup_render(scene, width, height, background):
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = SAMPLES
    scene.cycles.use_denoising = False  # flat colours: nothing to denoise, and it blurs lines
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = 'PNG'
    scene.render.image_settings.color_mode = 'RGB'
    scene.render.use_file_extension = False
    scene.view_settings.view_transform = 'Standard'  # a flat colour comes out as configured
    scene.view_settings.look = 'None'
    world = scene.world or bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = linear_rgba(background)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    # Freestyle: black outlines LINE_WIDTH_PX wide on silhouettes and borders, as toonwater's
    # outline shells draw them (no creases: marching-cubes meshes have them everywhere).
    scene.render.use_freestyle = True
    scene.render.line_thickness_mode = 'ABSOLUTE'
    scene.render.line_thickness = 1.0
    settings = scene.view_layers[0].freestyle_settings
    lineset = settings.linesets[0] if settings.linesets else settings.linesets.new("Outline")
    lineset.select_silhouette = True
    lineset.select_border = True
    lineset.select_crease = False
    lineset.linestyle.color = (0.0, 0.0, 0.0)
    lineset.linestyle.thickness = LINE_WIDTH_PX


def setup_camera(scene, view):
    data = bpy.data.cameras.new("Camera")
    data.sensor_fit = 'HORIZONTAL'  # POV-Ray's angle is the horizontal field of view
    data.angle = math.radians(view["angle"])
    camera = bpy.data.objects.new("Camera", data)
    scene.collection.objects.link(camera)
    camera.location = view["location"]
    forward = view["look_at"] - view["location"]
    camera.rotation_euler = forward.to_track_quat('-Z', 'Y').to_euler()  # world Z stays up
    scene.camera = camera


def render_frames(args, view):
    scene = bpy.context.scene
    for thing in list(scene.objects):
        bpy.data.objects.remove(thing)
    setup_render(scene, view["width"], view["height"], view["background"])
    setup_camera(scene, view)
    water = bpy.data.objects.new("Water", smooth_mesh("Water", [], []))
    transmit = view["water"]["transmit"] if args.see_through else 0.0
    water.data.materials.append(toon_material("Water", view["water"], view["light"], transmit))
    scene.collection.objects.link(water)
    thing = None
    if args.object:
        if "object" not in view:
            raise PeerError("%s: the scene has no object" % args.scene)
        thing = bpy.data.objects.new("Object", smooth_mesh("Object", [], []))
        thing.data.materials.append(toon_material("Object", view["object"], view["light"]))
        scene.collection.objects.link(thing)
    os.makedirs(args.out, exist_ok=True)
    for frame in range(args.first, args.last + 1):
        replace_mesh(water, smooth_mesh("Water", *read_bobj_gz(
            frame_path(args.water, frame), args.scale, args.translate)))
        if thing is not None:
            replace_mesh(thing, smooth_mesh("Object", *read_obj(frame_path(args.object, frame))))
        scene.frame_set(frame)
        final = os.path.join(args.out, "frame_%04d.png" % frame)
        staging = os.path.join(args.out, ".frame_%04d.png.part" % frame)
        scene.render.filepath = staging
        bpy.ops.render.render(write_still=True)
        if not os.path.isfile(staging):
            raise PeerError("%s: Blender wrote no image" % staging)
        os.replace(staging, final)
        print("cycles_toon: %s" % final, flush=True)


def replace_mesh(obj, mesh):
    old = obj.data
    mesh.materials.append(old.materials[0])
    obj.data = mesh
    bpy.data.meshes.remove(old)


def arguments(argv):
    parser = argparse.ArgumentParser(prog="cycles_toon.py")
    parser.add_argument("--scene", required=True, help="toonwater scene directory (--up z)")
    parser.add_argument("--water", required=True, help="Mantaflow mesh cache, ####.bobj.gz")
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--translate", default="0,0,0", help="X,Y,Z")
    parser.add_argument("--object", help="object OBJ per frame, ####.obj")
    parser.add_argument("--frames", required=True, help="FIRST-LAST")
    parser.add_argument("--see-through", action="store_true",
                        help="the water's free surface transmits as toonwater's (default: opaque)")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    try:
        args.translate = tuple(float(x) for x in args.translate.split(","))
        args.first, args.last = (int(x) for x in args.frames.split("-"))
    except ValueError:
        parser.error("--translate is X,Y,Z and --frames FIRST-LAST")
    if len(args.translate) != 3 or args.first > args.last:
        parser.error("--translate is X,Y,Z and --frames FIRST-LAST")
    return args


def main(argv):
    args = arguments(argv)
    render_frames(args, read_scene(args.scene))


if __name__ == "__main__":
    try:
        main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    except PeerError as e:
        print("cycles_toon: error: %s" % e, file=sys.stderr)
        sys.exit(1)
