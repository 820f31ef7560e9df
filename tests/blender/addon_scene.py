# The Blender test's scene, built from factory settings: a tiny Mantaflow liquid domain (a
# layer of water settling), a red sphere moving over it, a sun and a camera; baked into
# WORK/cache. Run inside Blender (tests/blender/test_addon.py imports it).
import math

import bpy
from mathutils import Vector

FRAMES = (1, 4)
RESOLUTION = (160, 90)
SPHERE_PATH = ((-0.5, 0.0, 0.8), (0.5, 0.0, 0.7))  # at the first and the last frame
SPHERE_COLOR = (0.8, 0.02, 0.02, 1.0)              # linear: distinctly red


def add_cube(name, location, dimensions):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = dimensions
    return obj


def look_from(obj, location, target):
    obj.location = location
    obj.rotation_euler = (Vector(target) - Vector(location)).to_track_quat('-Z', 'Y').to_euler()


def build(work):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = FRAMES
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100

    # A domain scaled unevenly and off the origin: the mesh cache's transform must follow it.
    domain = add_cube("Domain", (0.1, 0.0, 0.5), (2.0, 1.2, 1.0))
    water = add_cube("Water source", (0.1, 0.0, 0.2), (1.9, 1.1, 0.35))
    bpy.ops.object.modifier_add(type='FLUID')
    flow = water.modifiers[-1]
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'LIQUID'
    flow.flow_settings.flow_behavior = 'GEOMETRY'
    water.hide_render = True
    water.display_type = 'WIRE'

    bpy.context.view_layer.objects.active = domain
    domain.select_set(True)
    bpy.ops.object.modifier_add(type='FLUID')
    mod = domain.modifiers[-1]
    mod.fluid_type = 'DOMAIN'
    ds = mod.domain_settings
    ds.domain_type = 'LIQUID'
    ds.resolution_max = 20
    ds.use_mesh = True
    ds.cache_type = 'ALL'
    ds.cache_directory = work + "/cache"
    ds.cache_frame_start, ds.cache_frame_end = FRAMES

    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.2, location=SPHERE_PATH[0])
    sphere = bpy.context.active_object
    sphere.name = "Ball"
    material = bpy.data.materials.new("Red")
    material.diffuse_color = SPHERE_COLOR
    sphere.data.materials.append(material)
    for frame, location in zip(FRAMES, SPHERE_PATH):
        sphere.location = location
        sphere.keyframe_insert("location", frame=frame)

    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
    sun.data.color = (1.0, 0.9, 0.8)
    sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
    scene.collection.objects.link(sun)

    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(cam)
    look_from(cam, (0.6, -4.2, 2.2), (0.1, 0.0, 0.45))
    scene.camera = cam
    scene.frame_set(FRAMES[0])
    return domain, sphere, sun, cam


def bake(domain):
    bpy.context.view_layer.objects.active = domain
    result = bpy.ops.fluid.bake_all()
    if result != {'FINISHED'}:
        raise SystemExit("the Mantaflow bake did not finish: %s" % result)
