# The Cycles peer of bench/peer (issue 35) on one frame of the shared dam break, small: toonwater
# povgen writes the scene whose camera the peer reads, both render, and the pixels are checked:
# the peer's picture holds the water's three band colours and dark outlines along the water's
# silhouette, and frames the scene as toonwater's picture does.
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_cycles_peer.py \
#       -- --toonwater build/cli/toonwater --peer bench/peer/cycles_toon.py --data DIR --work DIR
# Exits 1 when a check fails, 77 (skipped) when the shared data is absent.
import argparse
import importlib.util
import os
import shutil
import subprocess
import sys

import bpy

FRAME = 18  # the run-up at the far wall: sheets, a crest, the sphere under water
WIDTH, HEIGHT = 320, 180
# A band colour counts where every channel is within this of it (8-bit steps).
COLOUR_TOLERANCE = 3 / 255
MIN_BAND_SHARE = 0.02  # of the picture, for each of the three bands (8–14 % on FRAME)
DARK = 0.2  # the outline: every channel below this
MIN_OUTLINED_RIM = 0.8  # share of the scene's rim pixels with a dark pixel within OUTLINE_REACH
OUTLINE_REACH = 2  # pixels
MAX_FRAMING_ERROR = 3  # pixels, for each edge of the scene's bounding box

results = {"passed": 0, "failed": 0}


def check(name, ok, detail=""):
    results["passed" if ok else "failed"] += 1
    print("%s: %s%s" % ("PASS" if ok else "FAIL", name, (" — " + detail) if detail else ""),
          flush=True)
    return ok


def arguments():
    parser = argparse.ArgumentParser()
    for name in ("--toonwater", "--peer", "--data", "--work"):
        parser.add_argument(name, required=True)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:])


def load_peer(path):
    spec = importlib.util.spec_from_file_location("cycles_toon", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def read_png(path):
    """Rows of (r, g, b) in [0, 1] as stored (sRGB), top row first."""
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = list(image.pixels)
    bpy.data.images.remove(image)
    rows = [[tuple(pixels[4 * (y * width + x):4 * (y * width + x) + 3]) for x in range(width)]
            for y in range(height)]
    return rows[::-1]  # Blender's rows start at the bottom


def near(a, b, tolerance):
    return all(abs(x - y) <= tolerance for x, y in zip(a, b))


def scene_mask(rows, background):
    return [[not near(p, background, 4 / 255) for p in row] for row in rows]


def bounding_box(mask):
    ys = [y for y, row in enumerate(mask) if any(row)]
    xs = [x for row in mask for x, inside in enumerate(row) if inside]
    return (min(xs), min(ys), max(xs), max(ys)) if xs else None


def outlined_rim_share(rows, mask):
    """Of the scene's pixels next to the background, the share with a dark pixel near."""
    height, width = len(rows), len(rows[0])
    rim = outlined = 0
    for y in range(1, height - 1):
        for x in range(1, width - 1):
            if not mask[y][x] or all(mask[y + dy][x + dx] for dy, dx in
                                     ((0, 1), (0, -1), (1, 0), (-1, 0))):
                continue
            rim += 1
            reach = range(-OUTLINE_REACH, OUTLINE_REACH + 1)
            if any(max(rows[yy][xx]) < DARK for yy in (min(height - 1, max(0, y + d)) for d in reach)
                   for xx in (min(width - 1, max(0, x + d)) for d in reach)):
                outlined += 1
    return outlined / rim if rim else 0.0


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        print(done.stdout[-2000:], done.stderr[-2000:])
        raise SystemExit("test_cycles_peer: %s exited with %d" % (command[1], done.returncode))


def main():
    args = arguments()
    mesh_pattern = os.path.join(args.data, "cache", "mesh", "fluid_mesh_####.bobj.gz")
    if not os.path.isfile(mesh_pattern.replace("####", "%04d" % FRAME)):
        print("SKIP: %s not found (../shared/data is not part of the repository)" % args.data)
        sys.exit(77)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    scene_dir = os.path.join(args.work, "scene")
    sphere = os.path.join(args.data, "sphere_####.obj")
    placement = ["--scale", "1.2", "--translate", "0,0,0.3"]
    run([args.toonwater, "povgen", "--water", mesh_pattern] + placement +
        ["--up", "z", "--object", sphere, "--set", "render.width=%d" % WIDTH,
         "--set", "render.height=%d" % HEIGHT, "--set", "render.frames=%d-%d" % (FRAME, FRAME),
         "--out", scene_dir])
    run([args.toonwater, "render", scene_dir])

    peer = load_peer(args.peer)
    view = peer.read_scene(scene_dir)
    peer_dir = os.path.join(args.work, "cycles")
    peer.main(["--scene", scene_dir, "--water", mesh_pattern] + placement +
              ["--object", sphere, "--frames", "%d-%d" % (FRAME, FRAME), "--out", peer_dir])
    cycles = read_png(os.path.join(peer_dir, "frame_%04d.png" % FRAME))
    toonwater = read_png(os.path.join(scene_dir, "frame.png"))

    check("picture size", (len(cycles[0]), len(cycles)) == (WIDTH, HEIGHT),
          "%d×%d" % (len(cycles[0]), len(cycles)))
    pixels = [p for row in cycles for p in row]
    for band in ("bright", "medium", "dark"):
        colour = view["water"][band]
        share = sum(near(p, colour, COLOUR_TOLERANCE) for p in pixels) / len(pixels)
        check("water's %s band in the picture" % band, share >= MIN_BAND_SHARE,
              "%.1f %% of the pixels (at least %.1f %%)" % (100 * share, 100 * MIN_BAND_SHARE))
    mask = scene_mask(cycles, view["background"])
    share = outlined_rim_share(cycles, mask)
    check("outline along the silhouette", share >= MIN_OUTLINED_RIM,
          "%.0f %% of the rim within %d px of a dark pixel" % (100 * share, OUTLINE_REACH))
    box = bounding_box(mask)
    expected = bounding_box(scene_mask(toonwater, view["background"]))
    check("framed as toonwater frames it",
          box is not None and expected is not None and
          max(abs(a - b) for a, b in zip(box, expected)) <= MAX_FRAMING_ERROR,
          "scene's box %s, toonwater's %s (x0, y0, x1, y1)" % (box, expected))
    print("test_cycles_peer: %d passed, %d failed" % (results["passed"], results["failed"]))
    sys.exit(1 if results["failed"] else 0)


main()
