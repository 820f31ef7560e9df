# The Toon water panel in the 3D Viewport's sidebar (N), tab "Toon Water".
import bpy

from . import operators


class TOONWATER_PT_panel(bpy.types.Panel):
    bl_label = "Toon Water"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Toon Water"

    def draw(self, context):
        s = context.scene.toonwater
        layout = self.layout
        layout.use_property_split = True
        if operators._running["job"] is None:
            layout.operator("toonwater.render", icon='RENDER_ANIMATION')
        else:
            layout.operator("toonwater.cancel", icon='CANCEL')
        layout.prop(s, "water_object")
        layout.prop(s, "output_directory")
        layout.prop(s, "quality")

        col = layout.column(heading="Bands", align=True)
        col.prop(s, "bright")
        col.prop(s, "medium")
        col.prop(s, "dark")

        col = layout.column()
        col.prop(s, "outline_enabled")
        sub = col.column()
        sub.active = s.outline_enabled
        sub.prop(s, "outline_width")
        sub.prop(s, "outline_color", text="Colour")

        col = layout.column()
        col.prop(s, "flow_enabled")
        sub = col.column()
        sub.active = s.flow_enabled
        sub.prop(s, "flow_style", text="Style")

        col = layout.column()
        col.prop(s, "reflection")
        sub = col.column()
        sub.active = s.reflection > 0
        sub.prop(s, "object_reflection", text="Objects")
        col.prop(s, "transmit")
        col.prop(s, "water_body")
