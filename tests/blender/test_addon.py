# The add-on tested in Blender, headless: installed from a zip, run on a tiny Mantaflow bake with
# a moving sphere, a sun and a camera; the configuration, the frames, the picture's geometry
# against Blender's world_to_camera_view, error reports and cancel are checked.
#   blender -b --factory-startup --python tests/blender/test_addon.py -- \
#       --toonwater build/cli/toonwater --addon blender/toonwater_addon --work DIR
# Exits 1 when a check fails. BLENDER_USER_SCRIPTS should point into DIR: the zip is installed
# there.
import argparse
import csv
import math
import os
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
import zipfile

import addon_utils
import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_scene  # noqa: E402

ADDON = "toonwater_addon"
# How far the sphere's centre in the picture may lie from Blender's projection of it (issue 34).
MAX_CENTRE_ERROR = 0.02  # of the image width

results = {"passed": 0, "failed": 0}


def check(name, ok, detail=""):
    results["passed" if ok else "failed"] += 1
    print("%s: %s%s" % ("PASS" if ok else "FAIL", name, (" — " + detail) if detail else ""),
          flush=True)
    return ok


def arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--toonwater", required=True)
    parser.add_argument("--addon", required=True)
    parser.add_argument("--work", required=True)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:])


def install_from_zip(addon_dir, work):
    path = os.path.join(work, ADDON + ".zip")
    with zipfile.ZipFile(path, "w") as z:
        for name in sorted(os.listdir(addon_dir)):
            if name.endswith(".py"):
                z.write(os.path.join(addon_dir, name), ADDON + "/" + name)
    bpy.ops.preferences.addon_install(filepath=path)
    addon_utils.enable(ADDON, default_set=True, handle_error=None)
    import toonwater_addon
    return toonwater_addon, bpy.context.preferences.addons[ADDON].preferences


def run_operator():
    """The operator's result, or the text of the error it reported."""
    try:
        return bpy.ops.toonwater.render(), ""
    except RuntimeError as e:
        return None, str(e)


def check_missing_program(prefs, work):
    prefs.toonwater_path = os.path.join(work, "no-such-toonwater")
    result, error = run_operator()
    check("a missing program in the preferences is one clear error",
          result is None and "is not an executable file" in error and "Traceback" not in error,
          error.strip())
    prefs.toonwater_path = ""
    path = os.environ["PATH"]
    os.environ["PATH"] = os.path.join(work, "empty-path")
    try:
        result, error = run_operator()
    finally:
        os.environ["PATH"] = path
    check("no toonwater on PATH is one clear error",
          result is None and "toonwater is not on PATH" in error, error.strip())
    check("nothing is written when the program is missing",
          not os.path.exists(os.path.join(work, "out", "inputs")))


def check_toonwater_error(scene, work):
    scene.render.resolution_x = 20000  # beyond render.width's range: toonwater refuses it
    try:
        result, error = run_operator()
    finally:
        scene.render.resolution_x = addon_scene.RESOLUTION[0]
    lines = [l for l in error.splitlines() if l.strip()]
    log = os.path.join(work, "out", "toonwater.log")
    check("toonwater's error is reported, one line, with the log's path",
          result is None and len(lines) == 1 and "render.width" in lines[0]
          and "(log: %s)" % log in lines[0], error.strip())


def check_configuration(scene, cam, sun, config_path):
    with open(config_path, "rb") as f:
        config = tomllib.load(f)
    c = config["camera"]
    m = cam.matrix_world
    location = Vector(c["location"])
    direction = (Vector(c["look_at"]) - location).normalized()
    forward = (m.to_3x3() @ Vector((0, 0, -1))).normalized()
    check("camera location is Blender's", (location - m.translation).length < 1e-6,
          "%s vs %s" % (tuple(location), tuple(m.translation)))
    check("camera direction is Blender's", (direction - forward).length < 1e-6)
    # Landscape with Auto sensor fit: the sensor's width spans the picture's width.
    angle = math.degrees(2 * math.atan(0.5 * cam.data.sensor_width / cam.data.lens))
    check("camera angle is Blender's horizontal field of view", abs(c["angle"] - angle) < 1e-4,
          "%r vs %r" % (c["angle"], angle))
    r = config["render"]
    check("image size is Blender's resolution",
          (r["width"], r["height"]) == addon_scene.RESOLUTION, str((r["width"], r["height"])))
    blender_fps = bpy.context.scene.render.fps / bpy.context.scene.render.fps_base
    check("frame rate is Blender's", r["fps"] == round(blender_fps), str(r["fps"]))
    towards_sun = (sun.matrix_world.to_3x3() @ Vector((0, 0, 1))).normalized()
    check("light direction points at Blender's sun",
          (Vector(config["light"]["direction"]) - towards_sun).length < 1e-6)
    srgb = [1.0, 0.9 ** (1 / 2.4) * 1.055 - 0.055, 0.8 ** (1 / 2.4) * 1.055 - 0.055]
    check("light colour is the sun's, in sRGB",
          all(abs(a - b) < 1e-6 for a, b in zip(config["light"]["color"], srgb)),
          str(config["light"]["color"]))
    objects = config.get("object", [])
    check("the sphere, and only it, is an object, exported per frame",
          [o["name"] for o in objects] == ["Ball"] and "####" in objects[0]["mesh"],
          str(objects))


def check_camera_conversion(addon, scene, cam):
    """Sensor fits, and the cameras toonwater cannot show refused with a reason."""
    w, h = addon_scene.RESOLUTION
    cam.data.sensor_fit = 'VERTICAL'
    vertical = 2 * math.atan(0.5 * cam.data.sensor_height / cam.data.lens)
    expected = math.degrees(2 * math.atan(math.tan(vertical / 2) * w / h))
    angle = addon.camera.camera_keys(scene)["angle"]
    check("vertical sensor fit: the horizontal angle follows from the vertical one",
          abs(angle - expected) < 1e-4, "%r vs %r" % (angle, expected))
    cam.data.sensor_fit = 'AUTO'
    # Portrait: Auto fits the sensor's width to the longer side, here the height.
    scene.render.resolution_x, scene.render.resolution_y = h, w
    longer = 2 * math.atan(0.5 * cam.data.sensor_width / cam.data.lens)
    expected = math.degrees(2 * math.atan(math.tan(longer / 2) * h / w))
    angle = addon.camera.camera_keys(scene)["angle"]
    check("portrait with Auto fit: the sensor spans the height",
          abs(angle - expected) < 1e-4, "%r vs %r" % (angle, expected))
    scene.render.resolution_x, scene.render.resolution_y = w, h
    refusals = [("rolled", lambda: cam.rotation_euler.rotate_axis('Z', math.radians(5)),
                 lambda: cam.rotation_euler.rotate_axis('Z', math.radians(-5))),
                ("shifted", lambda: setattr(cam.data, "shift_x", 0.1),
                 lambda: setattr(cam.data, "shift_x", 0.0)),
                ("not perspective", lambda: setattr(cam.data, "type", 'ORTHO'),
                 lambda: setattr(cam.data, "type", 'PERSP'))]
    for word, change, undo in refusals:
        change()
        bpy.context.view_layer.update()
        try:
            addon.camera.camera_keys(scene)
            message = ""
        except addon.camera.CameraError as e:
            message = str(e)
        undo()
        bpy.context.view_layer.update()
        check("a camera %s is refused with the reason" % word, word in message, message)


def check_water_placement(scene, domain, toonwater, out):
    """The mesh cache read with the transform the add-on gave povgen lands where Blender shows
    the liquid: toonwater analyze's vertices against the domain's evaluated mesh, frame 1."""
    with open(os.path.join(out, "toonwater.log")) as f:
        povgen = next(shlex.split(l[2:]) for l in f if l.startswith("$ ") and " povgen " in l)
    transform = povgen[povgen.index("--transform") + 1]
    cache = povgen[povgen.index("--water") + 1].replace("\\", "").replace("####", "%04d")
    frame = addon_scene.FRAMES[0]
    table = os.path.join(out, "water_check.csv")
    subprocess.run([toonwater, "analyze", cache % frame, "--up", "z", "--transform", transform,
                    "--csv", table], check=True, capture_output=True)
    with open(table) as f:
        ours = [Vector((float(r["x"]), float(r["y"]), float(r["z"]))) for r in csv.DictReader(f)]
    scene.frame_set(frame)
    evaluated = domain.evaluated_get(bpy.context.evaluated_depsgraph_get())
    blenders = [evaluated.matrix_world @ v.co for v in evaluated.data.vertices]
    same = len(ours) == len(blenders) > 0
    error = max((a - b).length for a, b in zip(ours, blenders)) if same else math.inf
    check("the mesh cache lands where Blender shows the liquid (uneven, moved domain)",
          same and error < 1e-4, "%d vs %d vertices, largest distance %.3g"
          % (len(ours), len(blenders), error))


def check_mesh_water(scene, settings, work):
    """Any mesh animated per frame as the water: exported frame by frame and rendered."""
    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(0.1, 0.0, 0.3))
    pond = bpy.context.active_object
    pond.name = "Pond"
    bpy.ops.object.modifier_add(type='SUBSURF')
    pond.modifiers[-1].subdivision_type = 'SIMPLE'
    pond.modifiers[-1].levels = 4
    bpy.ops.object.modifier_add(type='WAVE')  # the modifier's own animation, frame by frame
    pond.modifiers[-1].height = 0.05
    settings.water_object = pond
    settings.output_directory = os.path.join(work, "pond")
    result, error = run_operator()
    check("a mesh animated per frame renders as the water", result == {'FINISHED'}, error)
    water = os.path.join(work, "pond", "inputs", "water")
    names = sorted(os.listdir(water)) if os.path.isdir(water) else []
    texts = []
    for name in names:
        with open(os.path.join(water, name)) as f:
            texts.append(f.read())
    first, last = addon_scene.FRAMES
    check("the mesh water is exported for every frame, as it moves",
          names == ["Pond_%04d.obj" % f for f in range(first, last + 1)]
          and len(set(texts)) == len(texts), str(names))
    frames = os.listdir(os.path.join(work, "pond", "scene"))
    check("the mesh water's frames are rendered",
          all("frame_%d.png" % f in frames for f in range(first, last + 1)), str(frames))
    settings.water_object = None
    bpy.data.objects.remove(pond)


def red_centroid(path):
    """The centroid (x right, y up, in pixels) and pixel count of the picture's red pixels."""
    image = bpy.data.images.load(path)
    w, h = image.size
    px = image.pixels[:]
    bpy.data.images.remove(image)
    sx = sy = n = 0
    for i in range(w * h):
        r, g, b = px[4 * i:4 * i + 3]
        if r > 0.2 and r > 2.5 * g and r > 2.5 * b:
            sx += i % w + 0.5
            sy += i // w + 0.5  # Blender's pixels start at the bottom row
            n += 1
    return (sx / n, sy / n, n) if n else (None, None, 0), (w, h)


def check_projected_centres(scene, cam, sphere, scene_dir):
    for frame in addon_scene.FRAMES:
        scene.frame_set(frame)
        expected = world_to_camera_view(scene, cam, sphere.matrix_world.translation)
        (x, y, n), (w, h) = red_centroid(os.path.join(scene_dir, "frame_%d.png" % frame))
        if not check("frame %d shows the sphere" % frame, n > 50, "%d red pixels" % n):
            continue
        ex, ey = expected.x * w, expected.y * h
        error = math.hypot(x - ex, y - ey) / w
        check("frame %d: the sphere's centre lies where Blender projects it" % frame,
              error <= MAX_CENTRE_ERROR,
              "picture (%.1f, %.1f), Blender (%.1f, %.1f): %.2f %% of the width"
              % (x, y, ex, ey, 100 * error))
    scene.frame_set(addon_scene.FRAMES[0])


def descendants(pid):
    """Processes whose parent chain reaches `pid` (zombies left out)."""
    parents = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as f:
                    stat = f.read()
            except OSError:
                continue
            fields = stat[stat.rfind(")") + 2:].split()
            if fields[0] != "Z":
                parents[int(entry)] = int(fields[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def scene_folder_state(scene_dir):
    """Every file of the scene folder with its size and time, and whether it is complete."""
    names = sorted(os.listdir(scene_dir))
    with open(os.path.join(scene_dir, ".toonwater-scene")) as f:
        listed = [l.strip() for l in f.readlines()[1:] if l.strip()]  # after its title line
    return ({n: os.stat(os.path.join(scene_dir, n)).st_mtime_ns for n in names},
            [n for n in listed if n not in names],
            [n for n in names if n.startswith(".") and n != ".toonwater-scene"])


class Reports:
    def __init__(self):
        self.lines = []

    def report(self, kinds, text):
        self.lines.append((kinds, text))


def check_cancel(addon, scene, out_dir, when):
    """Starts a run, cancels it during `when` ("povgen" or "render") and checks what is left."""
    scene_dir = os.path.join(out_dir, "scene")
    before, _, _ = scene_folder_state(scene_dir)
    job, export = addon.operators.start_job(Reports(), bpy.context)
    started = {"povgen": set(), "render": set()}
    state = job.poll()
    deadline = time.monotonic() + 120
    while not state.finished and time.monotonic() < deadline:
        step = "render" if state.text.startswith("render") else "povgen"
        started[step] |= descendants(os.getpid())
        if step == when and (when == "povgen" or
                             addon.scene_export.rendered_frames(scene_dir)):
            break
        time.sleep(0.02)
        state = job.poll()
    check("cancel during %s: reached %s before the run finished" % (when, when),
          not state.finished, state.text)
    job.cancel()
    addon.operators._running["job"] = None
    check("cancel during %s: the job says it was cancelled" % when, job.poll().cancelled)
    left = descendants(os.getpid())
    check("cancel during %s: no process is left" % when, not left and
          not any(os.path.exists("/proc/%d" % p) and _name(p) for p in started[when]),
          "left: %s" % sorted(left))
    after, missing, temporaries = scene_folder_state(scene_dir)
    check("cancel during %s: the scene folder is complete, no temporaries" % when,
          not missing and not temporaries, "missing %s, temporaries %s" % (missing, temporaries))
    hidden = [n for n in os.listdir(out_dir) if n.startswith(".")]
    check("cancel during %s: no hidden staging folder beside the scene" % when, not hidden,
          str(hidden))
    if when == "povgen":
        check("cancel during povgen: the earlier scene is as it was", after == before)
    else:
        frames = addon.scene_export.rendered_frames(scene_dir)
        sizes = []
        for path in frames.values():
            image = bpy.data.images.load(path)
            sizes.append(tuple(image.size))
            bpy.data.images.remove(image)
        width, height = addon.camera.resolution(scene)
        check("cancel during render: every frame left is a whole picture of this run",
              all(s == (width, height) for s in sizes) and 0 < len(frames) < len(export.frames),
              "%d frames, sizes %s" % (len(frames), sizes))


def _name(pid):
    try:
        with open("/proc/%d/comm" % pid) as f:
            return f.read().strip()
    except OSError:
        return ""


def main():
    args = arguments()
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    addon, prefs = install_from_zip(os.path.abspath(args.addon), work)
    domain, sphere, sun, cam = addon_scene.build(work)
    start = time.monotonic()
    addon_scene.bake(domain)
    print("bake: %.1f s" % (time.monotonic() - start))
    scene = bpy.context.scene
    settings = scene.toonwater
    settings.output_directory = os.path.join(work, "out")
    settings.quality = 'PREVIEW'

    check_missing_program(prefs, work)
    prefs.toonwater_path = os.path.abspath(args.toonwater)
    check_toonwater_error(scene, work)

    start = time.monotonic()
    result, error = run_operator()
    print("operator: %.1f s" % (time.monotonic() - start))
    check("the operator finishes", result == {'FINISHED'}, error)
    out = os.path.join(work, "out")
    check_configuration(scene, cam, sun, os.path.join(out, "inputs", "scene.toml"))
    scene_dir = os.path.join(out, "scene")
    frames = addon.scene_export.rendered_frames(scene_dir)
    check("every frame is rendered", sorted(frames) == list(range(addon_scene.FRAMES[0],
                                                                  addon_scene.FRAMES[1] + 1)),
          str(sorted(frames)))
    image = bpy.data.images.get("Toon water")
    check("the frames are loaded as an image sequence",
          image is not None and image.source == 'SEQUENCE', str(image and image.filepath))
    check_projected_centres(scene, cam, sphere, scene_dir)
    check_camera_conversion(addon, scene, cam)
    check_water_placement(scene, domain, os.path.abspath(args.toonwater), out)

    check_mesh_water(scene, settings, work)
    settings.output_directory = out
    check_cancel(addon, scene, out, "povgen")
    # Larger, antialiased frames: the render lasts long enough to be cancelled while it runs.
    settings.quality = 'FINAL'
    scene.render.resolution_percentage = 400
    check_cancel(addon, scene, out, "render")

    print("%d passed, %d failed" % (results["passed"], results["failed"]))
    sys.exit(1 if results["failed"] else 0)


try:
    main()
except SystemExit:
    raise
except BaseException:
    import traceback
    traceback.print_exc()
    sys.exit(1)
