# A ball thrown into a tank, baked by Blender's Mantaflow, for overhead_study (issue #28's measures
# on a bake that is not in ../shared/data): a 1.6 × 1.6 × 0.8 m domain half full of water at rest;
# a collision sphere of radius 0.12 m waits above the domain until frame 10, enters the water at
# about 4 m/s and comes to rest near the floor by frame 22; 24 frames a second. The mesh cache
# (.bobj.gz, mesh_scale 1) goes to OUT/cache/mesh, the ball's frames to OUT/ball/ball_NNNN.obj,
# both in the mesh cache's normalised coordinates (domain centre 0, longest side 1): cell
# 1/RESOLUTION, tank -0.5,-0.5,-0.25 to 0.5,0.5,0 (the rest level).
#   blender -b --factory-startup --python mantaflow_ball_drop.py -- OUT [RESOLUTION] [FRAMES]
# (defaults 96 and 120: the waves settle from about frame 57).
import os
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not args:
    raise SystemExit("usage: blender -b --factory-startup --python mantaflow_ball_drop.py -- "
                     "OUT [RESOLUTION] [FRAMES]")
out = os.path.abspath(args[0])
resolution = int(args[1]) if len(args) > 1 else 96
frames = int(args[2]) if len(args) > 2 else 120
CENTRE_Z, LONGEST = 0.4, 1.6  # the domain's centre height and longest side
BALL_PATH = [(1, 1.0), (10, 1.0), (12, 0.62), (14, 0.36), (16, 0.22), (19, 0.14), (22, 0.13)]

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, frames
scene.render.fps = 24


def add_cube(name, location, dimensions):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = dimensions
    return obj


domain = add_cube("Domain", (0.0, 0.0, CENTRE_Z), (LONGEST, LONGEST, 0.8))
water = add_cube("Water", (0.0, 0.0, 0.2), (1.6, 1.6, 0.4))
bpy.ops.object.modifier_add(type='FLUID')
flow = water.modifiers[-1]
flow.fluid_type = 'FLOW'
flow.flow_settings.flow_type = 'LIQUID'
flow.flow_settings.flow_behavior = 'GEOMETRY'

bpy.ops.mesh.primitive_uv_sphere_add(radius=0.12, location=(0.1, -0.05, 1.0), segments=32,
                                     ring_count=16)
ball = bpy.context.active_object
ball.name = "Ball"
bpy.ops.object.modifier_add(type='FLUID')
effector = ball.modifiers[-1]
effector.fluid_type = 'EFFECTOR'
effector.effector_settings.effector_type = 'COLLISION'
effector.effector_settings.subframes = 2
for frame, z in BALL_PATH:
    ball.location = (0.1, -0.05, z)
    ball.keyframe_insert("location", frame=frame)
for curve in ball.animation_data.action.fcurves:
    for key in curve.keyframe_points:
        key.interpolation = 'LINEAR'

bpy.context.view_layer.objects.active = domain
bpy.ops.object.modifier_add(type='FLUID')
modifier = domain.modifiers[-1]
modifier.fluid_type = 'DOMAIN'
settings = modifier.domain_settings
settings.domain_type = 'LIQUID'
settings.resolution_max = resolution
settings.use_mesh = True
settings.mesh_scale = 1
settings.cache_type = 'ALL'
settings.cache_mesh_format = 'BOBJECT'
settings.cache_directory = out + "/cache"
settings.cache_frame_start, settings.cache_frame_end = 1, frames
if bpy.ops.fluid.bake_all() != {'FINISHED'}:
    raise SystemExit("the Mantaflow bake did not finish")

os.makedirs(out + "/ball", exist_ok=True)
for frame in range(1, frames + 1):
    scene.frame_set(frame)
    with open(out + "/ball/ball_%04d.obj" % frame, "w") as obj_file:
        for vertex in ball.data.vertices:
            p = ball.matrix_world @ vertex.co
            obj_file.write("v %.6f %.6f %.6f\n" %
                           (p.x / LONGEST, p.y / LONGEST, (p.z - CENTRE_Z) / LONGEST))
        for polygon in ball.data.polygons:
            obj_file.write("f " + " ".join(str(i + 1) for i in polygon.vertices) + "\n")
