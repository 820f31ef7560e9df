# Toon water: renders the scene's liquid as cartoon water with the toonwater program.
# Install this folder (or a zip of it) as an add-on; docs/blender.md is its manual.
bl_info = {
    "name": "Toon water",
    "author": "toonwater",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Sidebar (N) > Toon Water",
    "description": "Renders the liquid (Mantaflow or any mesh) as toon water with toonwater",
    "category": "Render",
}

if "bpy" in locals():  # a reload from Blender's add-on list
    import importlib
    from . import camera, job, look, operators, scene_export, scene_toml, ui
    for module in (scene_toml, job, camera, look, scene_export, operators, ui):
        importlib.reload(module)

import atexit

import bpy

from . import look, operators, ui

CLASSES = (look.ToonwaterSettings, look.ToonwaterPreferences, operators.TOONWATER_OT_render,
           operators.TOONWATER_OT_cancel, ui.TOONWATER_PT_panel)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.toonwater = bpy.props.PointerProperty(type=look.ToonwaterSettings)
    atexit.register(operators.stop_running_job)


def unregister():
    atexit.unregister(operators.stop_running_job)
    operators.stop_running_job()
    del bpy.types.Scene.toonwater
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
