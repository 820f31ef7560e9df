# Blender's active camera and sun as toonwater's [camera] and [light] keys, in Blender's own
# world coordinates (Z up: povgen runs with --up z). toonwater's camera keeps the world's up
# axis as the picture's up (POV-Ray's sky), so a rolled, shifted or orthographic camera, which
# it cannot show as Blender does, is refused with a message instead of rendered wrongly.
import math

from mathutils import Vector

# Beyond this, the picture would be visibly rotated against Blender's.
MAX_ROLL_DEGREES = 0.5


class CameraError(Exception):
    pass


def horizontal_angle_degrees(frame_corners):
    """The horizontal field of view from Camera.view_frame's four corners (camera space,
    the aspect and the sensor fit applied): 2·atan(half width / depth)."""
    xs = [c.x for c in frame_corners]
    depth = -frame_corners[0].z
    if abs(max(xs) + min(xs)) > 1e-6 * (max(xs) - min(xs)):
        raise CameraError("its lens is shifted (Shift X/Y): toonwater's camera looks through "
                          "the picture's centre")
    return math.degrees(2.0 * math.atan(0.5 * (max(xs) - min(xs)) / depth))


def roll_degrees(forward, camera_up):
    """The angle between the camera's up and the world's Z as seen along `forward`."""
    level_up = Vector((0.0, 0.0, 1.0)) - forward * forward.z
    if level_up.length < 1e-6:
        return 0.0  # looking straight up or down: refused by the caller
    level_up.normalize()
    return math.degrees(level_up.angle(camera_up))


def resolution(scene):
    """The rendered image's size in pixels, as Blender's render settings give it."""
    r = scene.render
    if abs(r.pixel_aspect_x - r.pixel_aspect_y) > 1e-6:
        raise CameraError("the render's pixel aspect is not 1:1")
    scale = r.resolution_percentage / 100.0
    return max(1, round(r.resolution_x * scale)), max(1, round(r.resolution_y * scale))


def camera_keys(scene):
    """{'location', 'look_at', 'angle'} of the scene's active camera."""
    cam = scene.camera
    if cam is None:
        raise CameraError("the scene has no active camera")
    if cam.data.type != 'PERSP':
        raise CameraError("camera '%s' is not perspective" % cam.name)
    m = cam.matrix_world
    rotation = m.to_3x3().normalized()
    forward = (rotation @ Vector((0.0, 0.0, -1.0))).normalized()
    up = (rotation @ Vector((0.0, 1.0, 0.0))).normalized()
    if abs(forward.z) > 0.9999:
        raise CameraError("camera '%s' looks straight up or down" % cam.name)
    roll = roll_degrees(forward, up)
    if roll > MAX_ROLL_DEGREES:
        raise CameraError("camera '%s' is rolled by %.1f°: toonwater keeps the horizon level"
                          % (cam.name, roll))
    try:
        angle = horizontal_angle_degrees(cam.data.view_frame(scene=scene))
    except CameraError as e:
        raise CameraError("camera '%s': %s" % (cam.name, e)) from None
    location = m.translation
    # look_at only gives the direction; a point as far away as the camera is from the origin
    # keeps the direction's precision when the scene's numbers are written.
    reach = max(1.0, location.length)
    return {"location": tuple(location), "look_at": tuple(location + forward * reach),
            "angle": angle}


def linear_to_srgb(c):
    """One colour channel from Blender's scene-linear to sRGB, clamped to [0, 1]."""
    c = min(1.0, max(0.0, c))
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def light_keys(scene):
    """[light] keys from the first visible sun by name (parallel rays), else the first point
    light (a position); {} with neither, and toonwater's default light is used."""
    lights = sorted((o for o in scene.objects
                     if o.type == 'LIGHT' and o.visible_get() and not o.hide_render),
                    key=lambda o: o.name)
    color = None
    for kind in ('SUN', 'POINT'):
        for light in lights:
            if light.data.type != kind:
                continue
            color = tuple(linear_to_srgb(c) for c in light.data.color)
            m = light.matrix_world
            if kind == 'SUN':  # a sun shines along its local -Z: towards it is +Z
                towards = (m.to_3x3() @ Vector((0.0, 0.0, 1.0))).normalized()
                return {"direction": tuple(towards), "color": color}
            return {"position": tuple(m.translation), "color": color}
    return {}
