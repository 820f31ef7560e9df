# A dam break baked by Blender's Mantaflow at a chosen resolution, for the input benchmarks
# (level_set_vs_mesh_cache.sh): a water column against the -X wall of a 1.6 × 1.0 × 0.8 domain
# (resolution_max 96: a 96 × 60 × 48 grid), the mesh cache (.bobj.gz) and a resumable OpenVDB
# data cache, whose data files hold the liquid level set `phi`; Blender's defaults otherwise.
#   blender -b --factory-startup --python mantaflow_dambreak.py -- OUT [RESOLUTION] [MESH_SCALE] [FRAMES]
# (defaults 96, 1, 16). The caches go to OUT/mesh and OUT/data.
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not args:
    raise SystemExit("usage: blender -b --factory-startup --python mantaflow_dambreak.py -- "
                     "OUT [RESOLUTION] [MESH_SCALE] [FRAMES]")
out = args[0]
resolution = int(args[1]) if len(args) > 1 else 96
mesh_scale = int(args[2]) if len(args) > 2 else 1
frames = int(args[3]) if len(args) > 3 else 16

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
bpy.context.scene.frame_start, bpy.context.scene.frame_end = 1, frames


def add_cube(name, location, dimensions):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location)
    obj = bpy.context.active_object
    obj.name = name
    obj.scale = dimensions
    return obj


domain = add_cube("Domain", (0.0, 0.0, 0.4), (1.6, 1.0, 0.8))
column = add_cube("Water", (-0.55, 0.0, 0.3), (0.45, 0.95, 0.55))
bpy.ops.object.modifier_add(type='FLUID')
flow = column.modifiers[-1]
flow.fluid_type = 'FLOW'
flow.flow_settings.flow_type = 'LIQUID'
flow.flow_settings.flow_behavior = 'GEOMETRY'

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
settings.cache_resumable = True  # the data files then hold phi
settings.cache_data_format = 'OPENVDB'
settings.cache_mesh_format = 'BOBJECT'
settings.cache_directory = out
settings.cache_frame_start, settings.cache_frame_end = 1, frames
if bpy.ops.fluid.bake_all() != {'FINISHED'}:
    raise SystemExit("the Mantaflow bake did not finish")
