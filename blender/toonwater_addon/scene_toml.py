# scene.toml text from validated values. Numbers are formatted here and every string is quoted
# by TOML's rules for basic strings, so no text a user typed reaches the file unescaped.
# Pure Python: no bpy, tested with plain python3 (tests/blender/test_addon_pure.py).
import math
import re
import struct

_BARE_KEY = re.compile(r"^[A-Za-z0-9_]+$")
# TOML basic strings: these must be escaped; other control characters as \uXXXX.
_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


def toml_string(text):
    """A TOML basic string holding `text` exactly."""
    out = []
    for ch in str(text):
        if ch in _ESCAPES:
            out.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append("\\u%04X" % ord(ch))
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def toml_float(value):
    """A finite number as a TOML float; NaN and infinity are refused."""
    x = float(value)
    if not math.isfinite(x):
        raise ValueError("not a finite number: %r" % value)
    text = _shortest(x)
    return text if any(c in text for c in ".en") else text + ".0"


def _shortest(x):
    """The shortest text, of 7 significant digits or more, that reads back as the same
    single-precision number (Blender's properties are single precision): 0.36, not
    0.36000001430511475. A value between two floats gets their precision, about 1e-7."""
    single = struct.pack("<f", x)
    for digits in range(7, 10):
        text = "%.*g" % (digits, x)
        if struct.pack("<f", float(text)) == single:
            return text
    return repr(x)


def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return toml_float(value)
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError("no TOML form for %r" % (value,))


def _key(name):
    if not _BARE_KEY.match(name):
        raise ValueError("not a bare TOML key: %r" % name)
    return name


def scene_toml(sections, objects=(), header=""):
    """The text of scene.toml: `sections` maps a table name to {key: value}; `objects` is a
    list of {key: value}, one [[object]] table each. Empty tables are left out."""
    lines = ["# " + line for line in header.splitlines()]
    for table, keys in sections.items():
        if not keys:
            continue
        lines += ["", "[" + _key(table) + "]"]
        lines += [_key(k) + " = " + toml_value(v) for k, v in keys.items()]
    for obj in objects:
        lines += ["", "[[object]]"]
        lines += [_key(k) + " = " + toml_value(v) for k, v in obj.items()]
    return "\n".join(lines).lstrip("\n") + "\n"


def escape_pattern(path):
    """A path made literal in a toonwater frame pattern: a backslash before # * ? [."""
    return re.sub(r"([#*?\[])", r"\\\1", path)
