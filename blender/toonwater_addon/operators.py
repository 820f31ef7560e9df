# "Render toon water": exports the scene, runs toonwater povgen and render as child processes
# with their progress in the status bar, then loads the frames as an image sequence.
# Interactively it is modal (a timer polls the job; Esc or the panel's Cancel stops it); in
# the background (blender -b, scripts) it runs to the end in execute.
import time

import bpy

from . import scene_export
from .job import ToonwaterJob, ToonwaterNotFound, find_toonwater

POLL_SECONDS = 0.2
IMAGE_NAME = "Toon water"

# The job running now (one at a time), so that the Cancel button can reach it.
_running = {"job": None, "cancel": False}


def stop_running_job():
    """Ends a running job with Blender (registered with atexit): no render outlives it."""
    if _running["job"] is not None:
        _running["job"].cancel()


def addon_preferences(context):
    addon = context.preferences.addons.get(__package__)
    return addon.preferences if addon else None


def start_job(operator, context):
    """Exports the scene and starts the job; None (with a report) when it cannot start."""
    prefs = addon_preferences(context)
    try:
        toonwater = find_toonwater(prefs.toonwater_path if prefs else "")
        export = scene_export.export_scene(context, toonwater)
    except (ToonwaterNotFound, scene_export.ExportError) as e:
        operator.report({'ERROR'}, "Toon water: " + str(e))
        return None, None
    except OSError as e:
        operator.report({'ERROR'}, "Toon water: could not write the inputs: %s" % e)
        return None, None
    for warning in export.warnings:
        operator.report({'WARNING'}, "Toon water: " + warning)
    job = ToonwaterJob(export.steps, export.out_dir, export.log_path)
    job.start()
    _running["job"], _running["cancel"] = job, False
    return job, export


def load_frames(context, export):
    """The rendered frames as one image sequence, shown in any open Image Editor."""
    frames = scene_export.rendered_frames(export.scene_dir)
    if not frames:
        return None
    first = min(frames)
    image = bpy.data.images.get(IMAGE_NAME)
    if image is not None:
        bpy.data.images.remove(image)
    image = bpy.data.images.load(frames[first])
    image.name = IMAGE_NAME
    image.source = 'SEQUENCE' if len(frames) > 1 else 'FILE'
    for window in context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == 'IMAGE_EDITOR':
                space = area.spaces.active
                space.image = image
                space.image_user.frame_start = first
                space.image_user.frame_offset = first - 1
                space.image_user.frame_duration = len(frames)
    return image


def finish_job(operator, context, job, export):
    """Reports how the job ended; returns the operator's result."""
    _running["job"] = None
    state = job.poll()
    if state.cancelled:
        operator.report({'WARNING'}, "Toon water: cancelled (log: %s)" % export.log_path)
        return {'CANCELLED'}
    if state.errors:
        for line in state.errors:
            operator.report({'ERROR'}, line)
        return {'CANCELLED'}
    image = load_frames(context, export)
    operator.report({'INFO'}, "Toon water: %d frame(s) in %s%s" % (
        len(export.frames), export.scene_dir,
        ", loaded as the image '%s'" % image.name if image else ""))
    return {'FINISHED'}


class TOONWATER_OT_render(bpy.types.Operator):
    """Render the scene's water as toon water with toonwater (POV-Ray)"""
    bl_idname = "toonwater.render"
    bl_label = "Render toon water"

    _timer = None

    def execute(self, context):
        job, export = start_job(self, context)
        if job is None:
            return {'CANCELLED'}
        while not job.poll().finished:
            if _running["cancel"]:
                job.cancel()
            time.sleep(POLL_SECONDS)
        return finish_job(self, context, job, export)

    def invoke(self, context, event):
        if bpy.app.background or _running["job"] is not None:
            if _running["job"] is not None:
                self.report({'ERROR'}, "Toon water: a render is already running")
                return {'CANCELLED'}
            return self.execute(context)
        self._job, self._export = start_job(self, context)
        if self._job is None:
            return {'CANCELLED'}
        wm = context.window_manager
        self._timer = wm.event_timer_add(POLL_SECONDS, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, 100)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'ESC' or _running["cancel"]:
            self._job.cancel()
            return self._end(context)
        if event.type == 'TIMER':
            state = self._job.poll()
            context.window_manager.progress_update(round(100 * state.fraction))
            context.workspace.status_text_set("Toon water: %s (%d %%)  Esc: cancel"
                                              % (state.text, round(100 * state.fraction)))
            if state.finished:
                return self._end(context)
        return {'PASS_THROUGH'}

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        return finish_job(self, context, self._job, self._export)


class TOONWATER_OT_cancel(bpy.types.Operator):
    """Stop the running toon water render; earlier outputs stay as they were"""
    bl_idname = "toonwater.cancel"
    bl_label = "Cancel"

    @classmethod
    def poll(cls, _context):
        return _running["job"] is not None

    def execute(self, _context):
        _running["cancel"] = True
        return {'FINISHED'}
