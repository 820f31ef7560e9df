# Blender Mantaflow bakes made on the spot for the benchmarks on real simulation output that is
# not in ../shared/data; Blender's defaults otherwise, 24 frames a second. Two scenes:
#   dambreak   a water column against the -X wall of a 1.6 × 1.0 × 0.8 m domain (resolution_max
#              96: a 96 × 60 × 48 grid); a resumable OpenVDB data cache, whose data files hold
#              the liquid level set `phi`, beside the mesh cache (level_set_vs_mesh_cache.sh).
#   ball-drop  a 1.6 × 1.6 × 0.8 m domain half full of water at rest; a collision ball of radius
#              0.12 m waits above the domain until frame 10, enters the water at about 4 m/s and
#              comes to rest near the floor by frame 22 (overhead_study). The ball's frames go to
#              OUT/ball/ball_NNNN.obj in the mesh cache's normalised coordinates (domain centre
#              0, longest side 1): cell 1/RESOLUTION, tank -0.5,-0.5,-0.25 to 0.5,0.5,0.
# The mesh cache (.bobj.gz) goes to OUT/cache/mesh, the data cache to OUT/cache/data.
#   blender -b --factory-startup --python mantaflow_bake.py -- SCENE OUT [RESOLUTION] [MESH_SCALE] [FRAMES]
# (defaults 96, 1, and 16 frames for dambreak, 120 for ball-drop: its waves settle from about
# frame 58).
import os
import sys

import bpy

SCENES = {"dambreak": 16, "ball-drop": 120}  # and their default frame counts
args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) < 2 or args[0] not in SCENES:
    raise SystemExit("usage: blender -b --factory-startup --python mantaflow_bake.py -- "
                     "dambreak|ball-drop OUT [RESOLUTION] [MESH_SCALE] [FRAMES]")
scene_name, out = args[0], os.path.abspath(args[1])
resolution = int(args[2]) if len(args) > 2 else 96
mesh_scale = int(args[3]) if len(args) > 3 else 1
frames = int(args[4]) if len(args) > 4 else SCENES[scene_name]


def add_cube(name, location, dimensions):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = dimensions
    return obj


def add_liquid(location, dimensions):
    water = add_cube("Water", location, dimensions)
    bpy.ops.object.modifier_add(type='FLUID')
    flow = water.modifiers[-1]
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'LIQUID'
    flow.flow_settings.flow_behavior = 'GEOMETRY'


def add_ball(radius, path):
    """A collision sphere moving along path, (frame, height) pairs, linearly."""
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=(0.1, -0.05, path[0][1]),
                                         segments=32, ring_count=16)
    ball = bpy.context.active_object
    ball.name = "Ball"
    bpy.ops.object.modifier_add(type='FLUID')
    effector = ball.modifiers[-1]
    effector.fluid_type = 'EFFECTOR'
    effector.effector_settings.effector_type = 'COLLISION'
    effector.effector_settings.subframes = 2
    for frame, z in path:
        ball.location = (0.1, -0.05, z)
        ball.keyframe_insert("location", frame=frame)
    for curve in ball.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = 'LINEAR'
    return ball


def write_normalised(obj, path, centre, longest):
    with open(path, "w") as obj_file:
        for vertex in obj.data.vertices:
            p = obj.matrix_world @ vertex.co
            obj_file.write("v %.6f %.6f %.6f\n" % tuple((p[i] - centre[i]) / longest for i in range(3)))
        for polygon in obj.data.polygons:
            obj_file.write("f " + " ".join(str(i + 1) for i in polygon.vertices) + "\n")


for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, frames
scene.render.fps = 24

ball = None
centre, longest = (0.0, 0.0, 0.4), 1.6  # the domain's; the mesh cache's normalisation
if scene_name == "dambreak":
    domain = add_cube("Domain", centre, (longest, 1.0, 0.8))
    add_liquid((-0.55, 0.0, 0.3), (0.45, 0.95, 0.55))
else:
    domain = add_cube("Domain", centre, (longest, longest, 0.8))
    add_liquid((0.0, 0.0, 0.2), (1.6, 1.6, 0.4))
    ball = add_ball(0.12, [(1, 1.0), (10, 1.0), (12, 0.62), (14, 0.36), (16, 0.22), (19, 0.14),
                           (22, 0.13)])

bpy.context.view_layer.objects.active = domain
bpy.ops.object.modifier_add(type='FLUID')
modifier = domain.modifiers[-1]
modifier.fluid_type = 'DOMAIN'
settings = modifier.domain_settings
settings.domain_type = 'LIQUID'
settings.resolution_max = resolution
settings.use_mesh = True
settings.mesh_scale = mesh_scale
settings.cache_type = 'ALL'
settings.cache_resumable = scene_name == "dambreak"  # the data files then hold phi
settings.cache_data_format = 'OPENVDB'
settings.cache_mesh_format = 'BOBJECT'
settings.cache_directory = out + "/cache"
settings.cache_frame_start, settings.cache_frame_end = 1, frames
if bpy.ops.fluid.bake_all() != {'FINISHED'}:
    raise SystemExit("the Mantaflow bake did not finish")

if ball:
    os.makedirs(out + "/ball", exist_ok=True)
    for frame in range(1, frames + 1):
        scene.frame_set(frame)
        write_normalised(ball, out + "/ball/ball_%04d.obj" % frame, centre, longest)
