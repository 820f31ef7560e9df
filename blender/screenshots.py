# The screenshots of docs/blender.md, taken in Blender's own window under Xvfb (not run by CI):
#   xvfb-run -a -s "-screen 0 1280x800x24" blender -b --factory-startup \
#       --python blender/screenshots.py -- build/cli/toonwater docs/images WORK
# In the background it builds and bakes the test scene (tests/blender/addon_scene.py) and saves
# it as WORK/scene.blend; then it opens that file in a window (no splash screen over it), shows
# the add-on's tab, starts "Render toon water" and photographs the panel, the status bar during
# the render and the frames loaded back, then quits.
import os
import subprocess
import sys

import addon_utils
import bpy

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "tests", "blender")]
import addon_scene  # noqa: E402

toonwater, images, work = [os.path.abspath(a) for a in sys.argv[sys.argv.index("--") + 1:]]
blend = os.path.join(work, "scene.blend")
# Where the sidebar's "Toon Water" tab is, below the region's top, at the default interface
# scale (Blender 3.4 has no API that picks a sidebar tab, so it is clicked).
TAB_BELOW_TOP = 179
PANEL_HEIGHT = 470


def build_and_open():
    os.makedirs(work, exist_ok=True)
    addon_utils.enable("toonwater_addon", default_set=True)
    domain, *_ = addon_scene.build(work)
    addon_scene.bake(domain)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 480, 270
    scene.frame_end = 2
    scene.toonwater.output_directory = "//out/"
    bpy.ops.wm.save_as_mainfile(filepath=blend)
    subprocess.run([bpy.app.binary_path, "--factory-startup", blend, "--enable-event-simulate",
                    "--python", os.path.abspath(__file__), "--", toonwater, images, work],
                   check=True)


def crop_window_shot(path, x, y, w, h):
    """Keeps the window's rectangle (x, y from the bottom left) of the screenshot at `path`."""
    shot = bpy.data.images.load(path)
    full_w = shot.size[0]
    px = shot.pixels[:]
    out = bpy.data.images.new("crop", w, h)
    out.pixels = [v for r in range(h)
                  for v in px[4 * ((y + r) * full_w + x):4 * ((y + r) * full_w + x + w)]]
    out.filepath_raw = path
    out.file_format = 'PNG'
    out.save()
    bpy.data.images.remove(shot)
    bpy.data.images.remove(out)


def window():
    return bpy.context.window_manager.windows[0]


def window_shot(name, rect):
    path = os.path.join(images, name)
    with bpy.context.temp_override(window=window()):
        bpy.ops.screen.screenshot(filepath=path)
    crop_window_shot(path, *rect)
    print("screenshot:", path)


def area_of(kind):
    return next(a for a in window().screen.areas if a.type == kind)


def sidebar():
    return next(r for r in area_of('VIEW_3D').regions if r.type == 'UI')


def show_tab():
    addon_utils.enable("toonwater_addon", default_set=True)
    bpy.context.preferences.addons["toonwater_addon"].preferences.toonwater_path = toonwater
    area_of('VIEW_3D').spaces.active.show_region_ui = True
    return 1.0


def click_tab():
    r = sidebar()
    x, y = r.x + r.width - 12, r.y + r.height - TAB_BELOW_TOP
    for kind, value in (('MOUSEMOVE', 'NOTHING'), ('LEFTMOUSE', 'PRESS'),
                        ('LEFTMOUSE', 'RELEASE')):
        window().event_simulate(type=kind, value=value, x=x, y=y)
    return 1.0


def panel():
    r = sidebar()
    window_shot("blender-panel.png", (r.x, r.y + r.height - PANEL_HEIGHT, r.width, PANEL_HEIGHT))
    area = area_of('VIEW_3D')
    region = next(g for g in area.regions if g.type == 'WINDOW')
    with bpy.context.temp_override(window=window(), area=area, region=region):
        bpy.ops.toonwater.render('INVOKE_DEFAULT')
    return 1.0


def progress():
    window_shot("blender-progress.png", (0, 0, window().width, 24))
    return 0.5


def frames():
    from toonwater_addon import operators
    if operators._running["job"] is not None:
        return 0.5
    area = area_of('VIEW_3D')
    area.type = 'IMAGE_EDITOR'
    area.spaces.active.image = bpy.data.images["Toon water"]
    return 1.0


def frames_shot():
    area = area_of('IMAGE_EDITOR')
    region = next(g for g in area.regions if g.type == 'WINDOW')
    with bpy.context.temp_override(window=window(), area=area, region=region):
        bpy.ops.image.view_all(fit_view=True)
    window_shot("blender-frames.png", (area.x, area.y, area.width, area.height))
    bpy.ops.wm.quit_blender()


steps = [show_tab, click_tab, panel, progress, frames, frames_shot]


def run_steps():
    step = steps[0]
    result = step()
    if step is not frames or result == 1.0:
        steps.pop(0)
    return result


if bpy.app.background:
    build_and_open()
else:
    bpy.app.timers.register(run_steps, first_interval=2.0)
