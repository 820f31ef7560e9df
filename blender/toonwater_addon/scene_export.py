# From the Blender scene to toonwater's inputs: the liquid (a Mantaflow mesh cache with the
# domain's transform, or any mesh exported frame by frame), the obstacles (static, or per frame
# where they move), scene.toml, and the povgen and render command lines.
import os
import re
import shutil

import bpy
from mathutils import Matrix, Vector

from . import camera, look, scene_toml
from .job import Step

# Marks a folder the add-on wrote, so that only such a folder is ever replaced or removed.
MARKER = ".toonwater-addon"
CACHE_NAMES = {'BOBJECT': "fluid_mesh_%s.bobj.gz", 'OBJECT': "fluid_mesh_%s.obj"}


class ExportError(Exception):
    pass


def liquid_domain_settings(obj):
    """The domain settings of a Mantaflow liquid domain, else None."""
    for mod in getattr(obj, "modifiers", ()):
        if mod.type == 'FLUID' and mod.fluid_type == 'DOMAIN' and \
                mod.domain_settings.domain_type == 'LIQUID':
            return mod.domain_settings
    return None


def is_fluid_flow(obj):
    return any(m.type == 'FLUID' and m.fluid_type == 'FLOW' for m in obj.modifiers)


def renders(obj):
    return obj.visible_get() and not obj.hide_render


def water_object(scene, settings):
    """The panel's water object, else the scene's one visible liquid domain."""
    if settings.water_object is not None:
        return settings.water_object
    domains = [o for o in scene.objects if renders(o) and liquid_domain_settings(o)]
    if len(domains) != 1:
        raise ExportError("choose the water object on the panel (the scene has %d visible "
                          "liquid domains)" % len(domains))
    return domains[0]


def obstacles(scene, water):
    """The visible mesh objects but the water and Mantaflow's liquid sources, by name."""
    return sorted((o for o in scene.objects
                   if o.type == 'MESH' and o != water and renders(o) and not is_fluid_flow(o)
                   and not liquid_domain_settings(o)), key=lambda o: o.name)


def domain_transform(domain):
    """[A | b] taking the mesh cache's normalised coordinates to world (docs/inputs.md):
    the domain mesh's longest side, its rotation and scale, its bounding box's centre."""
    corners = [v.co for v in domain.data.vertices]  # the domain's own mesh, not the liquid
    lo = Vector(map(min, zip(*corners)))
    hi = Vector(map(max, zip(*corners)))
    s = domain.matrix_world.to_scale()
    longest = max((hi - lo)[i] * abs(s[i]) for i in range(3))
    m = domain.matrix_world
    a = m.to_3x3() @ Matrix.Diagonal([longest / abs(s[i]) for i in range(3)])
    b = m @ ((lo + hi) / 2)
    return [x for i in range(3) for x in (*a[i], b[i])]


def frame_digits(last):
    return max(4, len(str(last)))


def cache_frames(settings, frame_range):
    """The mesh cache's file pattern and the scene's frames it holds (consecutive)."""
    if not settings.use_mesh:
        raise ExportError("the liquid domain's Mesh option is off: turn it on and bake the mesh")
    name = CACHE_NAMES.get(settings.cache_mesh_format)
    if name is None:
        raise ExportError("the liquid domain's mesh cache format %s is not read by toonwater "
                          "(use Binary Object)" % settings.cache_mesh_format)
    folder = os.path.join(bpy.path.abspath(settings.cache_directory), "mesh")
    present = [f for f in frame_range if os.path.isfile(os.path.join(folder, name % ("%04d" % f)))]
    if not present:
        raise ExportError("no baked mesh in %s for frames %d-%d: bake the domain's mesh"
                          % (folder, frame_range[0], frame_range[-1]))
    if present != list(range(present[0], present[-1] + 1)):
        missing = next(f for f in range(present[0], present[-1]) if f not in present)
        raise ExportError("the mesh cache in %s has no frame %d" % (folder, missing))
    pattern = os.path.join(scene_toml.escape_pattern(folder), name % "####")
    return pattern, present


def world_mesh_obj(obj, depsgraph):
    """An object's evaluated mesh at the current frame as OBJ text in world coordinates."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        m = evaluated.matrix_world
        mesh.calc_loop_triangles()
        lines = ["v %r %r %r" % tuple(m @ v.co) for v in mesh.vertices]
        lines += ["f %d %d %d" % tuple(i + 1 for i in t.vertices) for t in mesh.loop_triangles]
    finally:
        evaluated.to_mesh_clear()
    return "\n".join(lines) + "\n"


def export_sequences(context, objects, frames, folder, static_when_still=True):
    """Writes each object's mesh for every frame; an object identical in every frame is kept
    as one static file (with `static_when_still`). Returns {object name: path relative to
    `folder`'s parent}."""
    scene = context.scene
    texts = {o.name: [] for o in objects}
    current = scene.frame_current
    try:
        for f in frames:
            scene.frame_set(f)
            depsgraph = context.evaluated_depsgraph_get()
            for o in objects:
                texts[o.name].append(world_mesh_obj(o, depsgraph))
    finally:
        scene.frame_set(current)
    os.makedirs(folder, exist_ok=True)
    paths, used = {}, set()
    digits = frame_digits(frames[-1])
    for o in objects:
        stem = re.sub(r"[^A-Za-z0-9_]", "_", o.name)
        while stem in used:
            stem += "_"
        used.add(stem)
        if static_when_still and all(t == texts[o.name][0] for t in texts[o.name]):
            write_text(os.path.join(folder, stem + ".obj"), texts[o.name][0])
            paths[o.name] = os.path.basename(folder) + "/" + stem + ".obj"
        else:
            for f, text in zip(frames, texts[o.name]):
                write_text(os.path.join(folder, "%s_%0*d.obj" % (stem, digits, f)), text)
            paths[o.name] = os.path.basename(folder) + "/" + stem + "_" + "#" * digits + ".obj"
    return paths


def write_text(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def object_color(obj):
    """The object's viewport colour (its material's, else none) as sRGB."""
    material = obj.active_material
    if material is None:
        return None
    return tuple(camera.linear_to_srgb(c) for c in material.diffuse_color[:3])


def replace_folder(staging, final):
    """Puts the complete `staging` folder at `final`, replacing only a folder the add-on wrote."""
    if os.path.exists(final):
        if not os.path.isfile(os.path.join(final, MARKER)):
            raise ExportError("%s exists and was not written by the add-on: choose another "
                              "output folder" % final)
        old = final + ".old"
        if os.path.exists(old):
            shutil.rmtree(old)
        os.rename(final, old)
        os.rename(staging, final)
        shutil.rmtree(old)
    else:
        os.rename(staging, final)


def new_staging(path):
    """An empty folder at `path` marked as the add-on's; a stale one of its own is removed."""
    if os.path.exists(path):
        if not os.path.isfile(os.path.join(path, MARKER)):
            raise ExportError("%s exists and was not written by the add-on" % path)
        shutil.rmtree(path)
    os.makedirs(path)
    write_text(os.path.join(path, MARKER), "written by the Toon water Blender add-on\n")


class Export:
    """What one run needs: the output folder, the frames and the two commands."""

    def __init__(self, out_dir, frames, steps, warnings):
        self.out_dir = out_dir
        self.frames = frames
        self.steps = steps
        self.warnings = warnings
        self.scene_dir = os.path.join(out_dir, "scene")
        self.log_path = os.path.join(out_dir, "toonwater.log")


def rendered_frames(scene_dir):
    """The frames POV-Ray wrote in the scene folder, by frame number."""
    frames = {}
    for name in os.listdir(scene_dir) if os.path.isdir(scene_dir) else ():
        number = re.fullmatch(r"frame_(\d+)\.png", name)
        if number:
            frames[int(number.group(1))] = os.path.join(scene_dir, name)
    return dict(sorted(frames.items()))


def remove_frames(scene_dir):
    """Removes an earlier render's frames, which povgen keeps in the scene it replaces, so
    that the frames there are always the current scene's."""
    for path in rendered_frames(scene_dir).values():
        os.remove(path)


def output_folder(settings):
    path = settings.output_directory
    if path.startswith("//") and not bpy.data.filepath:
        raise ExportError("save the .blend file first, or give the output folder as an "
                          "absolute path (it is relative to the .blend file)")
    return os.path.normpath(bpy.path.abspath(path))


def write_inputs(context, settings, toonwater, water, staging, frame_range, camera_keys, size):
    """Writes scene.toml and the meshes into `staging`; returns povgen's command and the
    frames."""
    scene = context.scene
    domain = liquid_domain_settings(water)
    povgen = [toonwater, "povgen", "--up", "z", "--config", "inputs/scene.toml", "--out", "scene"]
    if domain is not None:
        pattern, frames = cache_frames(domain, frame_range)
        povgen += ["--water", pattern,
                   "--transform", ",".join(repr(x) for x in domain_transform(water))]
    else:
        if water.type != 'MESH':
            raise ExportError("the water object '%s' is not a mesh" % water.name)
        frames = frame_range
        # A sequence even where the water does not move: a single file would be rendered as
        # frame 0, and the frames keep Blender's numbers.
        water_path = export_sequences(context, [water], frames, os.path.join(staging, "water"),
                                      static_when_still=False)[water.name]
        povgen += ["--water", "inputs/" + water_path]

    things = obstacles(scene, water)
    paths = export_sequences(context, things, frames, os.path.join(staging, "objects")) \
        if things else {}
    objects = []
    for o in things:
        entry = {"name": o.name, "mesh": paths[o.name]}
        color = object_color(o)
        if color is not None:
            entry["color"] = color
        entry["reflection"] = look.OBJECT_REFLECTION[settings.object_reflection]
        objects.append(entry)

    sections = look.look_sections(settings)
    sections["camera"] = camera_keys
    sections["light"] = camera.light_keys(scene)
    # render.fps is a whole number of frames a second (1-240): NTSC's 29.97 plays at 30.
    fps = max(1, min(240, round(scene.render.fps / scene.render.fps_base)))
    sections["render"].update({"width": size[0], "height": size[1],
                               "frames": "%d-%d" % (frames[0], frames[-1]), "fps": fps})
    header = ("Written by the Toon water Blender add-on from %s, scene '%s'.\n"
              "Blender's world coordinates, Z up: povgen --up z." %
              (bpy.data.filepath or "an unsaved file", scene.name))
    write_text(os.path.join(staging, "scene.toml"),
               scene_toml.scene_toml(sections, objects, header))
    return povgen, frames


def export_scene(context, toonwater):
    """Writes inputs/ (scene.toml, meshes) under the output folder, whole or not at all."""
    scene = context.scene
    settings = scene.toonwater
    try:
        camera_keys = camera.camera_keys(scene)
        width, height = camera.resolution(scene)
    except camera.CameraError as e:
        raise ExportError(str(e)) from None
    out_dir = output_folder(settings)
    water = water_object(scene, settings)
    frame_range = list(range(scene.frame_start, scene.frame_end + 1))

    os.makedirs(out_dir, exist_ok=True)
    inputs = os.path.join(out_dir, "inputs")
    staging = os.path.join(out_dir, "inputs.partial")
    new_staging(staging)
    try:
        povgen, frames = write_inputs(context, settings, toonwater, water, staging, frame_range,
                                      camera_keys, (width, height))
        replace_folder(staging, inputs)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)  # a failed export leaves nothing behind
        raise

    warnings = []
    if not camera.light_keys(scene):
        warnings.append("the scene has no visible sun or point light: toonwater's default "
                        "light is used")
    render = [toonwater, "render", "scene"]
    scene_dir = os.path.join(out_dir, "scene")
    return Export(out_dir, frames, [Step("povgen", povgen),
                                    Step("render", render, lambda: remove_frames(scene_dir))],
                  warnings)
