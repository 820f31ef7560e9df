# The look's main settings on the panel, stored in the .blend with the scene, and their
# scene.toml keys. The defaults are toonwater's own (docs/scenes.md), named here once.
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, \
    PointerProperty, StringProperty

BRIGHT = (0.36, 0.64, 0.88)
MEDIUM = (0.2, 0.46, 0.76)
DARK = (0.08, 0.26, 0.56)
OUTLINE_COLOR = (0.0, 0.0, 0.0)
OUTLINE_WIDTH_PIXELS = 2.0
REFLECTION = 0.2
TRANSMIT = 0.4

FLOW_STYLES = {'REGIONS': "regions", 'LINES': "lines", 'REGIONS_LINES': "regions+lines"}
WATER_BODIES = {'OPAQUE': "opaque", 'CLEAR': "clear"}
OBJECT_REFLECTION = {'CONCRETE': "concrete", 'ABSTRACT': "abstract", 'NONE': "none"}
QUALITIES = {'DRAFT': "draft", 'PREVIEW': "preview", 'FINAL': "final"}


def _color(name, default, description):
    # COLOR_GAMMA: the values are the sRGB ones the colour picker shows, as scene.toml takes.
    return FloatVectorProperty(name=name, default=default, size=3, min=0.0, max=1.0,
                               subtype='COLOR_GAMMA', description=description)


def _is_mesh(_settings, obj):
    return obj.type == 'MESH'


class ToonwaterSettings(bpy.types.PropertyGroup):
    water_object: PointerProperty(
        name="Water", type=bpy.types.Object, poll=_is_mesh,
        description="The liquid domain (its Mantaflow mesh cache is read) or any mesh "
                    "animated per frame; empty: the scene's one liquid domain")
    output_directory: StringProperty(
        name="Output", subtype='DIR_PATH', default="//toonwater/",
        description="Folder for the inputs, the POV-Ray scene, the frames and the log")
    bright: _color("Bright", BRIGHT, "The bright band's colour")
    medium: _color("Medium", MEDIUM, "The medium band's colour")
    dark: _color("Dark", DARK, "The dark band's colour")
    outline_enabled: BoolProperty(name="Outlines", default=True,
                                  description="Draw outlines around the water and objects")
    outline_width: FloatProperty(name="Width", default=OUTLINE_WIDTH_PIXELS, min=0.1, max=50.0,
                                 description="Outline width in pixels")
    outline_color: _color("Line colour", OUTLINE_COLOR, "The outlines' colour")
    flow_enabled: BoolProperty(name="Flow", default=True,
                               description="Draw the water's flow (crests and troughs)")
    flow_style: EnumProperty(
        name="Flow style", default='REGIONS',
        items=[('REGIONS', "Regions", "Crests and troughs as filled regions"),
               ('LINES', "Lines", "Crests and troughs as strokes"),
               ('REGIONS_LINES', "Regions and lines", "Both")])
    reflection: FloatProperty(name="Reflection", default=REFLECTION, min=0.0, max=1.0,
                              description="Weight of the reflected ray (0: no reflection)")
    object_reflection: EnumProperty(
        name="Objects reflected", default='CONCRETE',
        items=[('CONCRETE', "As they are", "Objects are reflected as they are"),
               ('ABSTRACT', "Silhouettes", "Only the objects' flat silhouettes"),
               ('NONE', "Not at all", "Objects are not reflected")])
    transmit: FloatProperty(name="Refraction", default=TRANSMIT, min=0.0, max=1.0,
                            description="Share of the refracted ray (0: opaque water)")
    water_body: EnumProperty(
        name="Body", default='OPAQUE',
        items=[('OPAQUE', "Opaque", "See-through surface over an opaque body"),
               ('CLEAR', "Clear", "The whole volume is see-through")])
    quality: EnumProperty(
        name="Quality", default='FINAL',
        items=[('DRAFT', "Draft", "Half size, no antialiasing"),
               ('PREVIEW', "Preview", "Full size, no antialiasing"),
               ('FINAL', "Final", "Full size, antialiased")])


class ToonwaterPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    toonwater_path: StringProperty(
        name="toonwater program", subtype='FILE_PATH', default="",
        description="Path of the toonwater program; empty: toonwater on PATH")

    def draw(self, _context):
        self.layout.prop(self, "toonwater_path")


def look_sections(s):
    """The panel's look as scene.toml tables (the caller adds camera, light and render)."""
    flow = {"enabled": s.flow_enabled}
    if s.flow_enabled:
        flow["style"] = FLOW_STYLES[s.flow_style]
    return {
        "water": {"bright": tuple(s.bright), "medium": tuple(s.medium), "dark": tuple(s.dark),
                  "reflection": s.reflection, "transmit": s.transmit,
                  "body": WATER_BODIES[s.water_body]},
        "outline": {"enabled": s.outline_enabled, "width": s.outline_width,
                    "units": "pixels", "color": tuple(s.outline_color)},
        "flow": flow,
        "render": {"quality": QUALITIES[s.quality]},
    }
