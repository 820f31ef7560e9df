# The add-on's parts that need no Blender, under plain python3: scene.toml text read back by
# Python's own TOML reader, frame patterns, finding the program, and toonwater's errors turned
# into report lines. TOONWATER_ADDON_DIR and TOONWATER_EXECUTABLE come from CTest.
import math
import os
import stat
import struct
import sys
import tempfile
import time
import tomllib
import unittest

sys.path.insert(0, os.environ["TOONWATER_ADDON_DIR"])
import job  # noqa: E402
import scene_toml  # noqa: E402

TOONWATER = os.environ["TOONWATER_EXECUTABLE"]


def single(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


class TomlText(unittest.TestCase):
    def test_strings_read_back_exactly(self):
        for text in ['plain', 'quote " and \\ backslash', "tab\tnew\nline\r\f\b",
                     "control \x01\x1f\x7f", "unicode ÅØ 水 🌊", 'x"\n[camera]\nangle = 1',
                     "", "'single'", "trailing \\"]:
            doc = tomllib.loads("key = " + scene_toml.toml_string(text) + "\n")
            self.assertEqual(doc, {"key": text}, text)

    def test_numbers_are_floats_that_read_back(self):
        for x in [0.0, 1.0, -2.5, 1e-30, 123456789.0, single(0.36), single(0.1) * 3, 1e18]:
            text = scene_toml.toml_float(x)
            value = tomllib.loads("x = " + text)["x"]
            self.assertIsInstance(value, float, text)
            self.assertEqual(single(value), single(x), text)
        self.assertEqual(scene_toml.toml_float(single(0.36)), "0.36")
        self.assertEqual(scene_toml.toml_float(640), "640.0")

    def test_non_finite_numbers_are_refused(self):
        for x in [math.nan, math.inf, -math.inf]:
            with self.assertRaises(ValueError):
                scene_toml.toml_float(x)

    def test_document_reads_back(self):
        sections = {"camera": {"location": (1.5, -4.0, 2.25), "angle": 39.5},
                    "render": {"width": 160, "frames": "1-4", "antialias": False},
                    "light": {}}
        objects = [{"name": 'Ball "one"\n[x]', "mesh": "objects/Ball_####.obj"},
                   {"name": "Two", "mesh": "objects/Two.obj", "color": (0.5, 0.25, 1.0)}]
        doc = tomllib.loads(scene_toml.scene_toml(sections, objects, "header\nline two"))
        self.assertEqual(doc, {"camera": {"location": [1.5, -4.0, 2.25], "angle": 39.5},
                               "render": {"width": 160, "frames": "1-4", "antialias": False},
                               "object": [{"name": 'Ball "one"\n[x]',
                                           "mesh": "objects/Ball_####.obj"},
                                          {"name": "Two", "mesh": "objects/Two.obj",
                                           "color": [0.5, 0.25, 1.0]}]})

    def test_keys_must_be_bare(self):
        for key in ["a.b", "a b", "", 'a"']:
            with self.assertRaises(ValueError):
                scene_toml.scene_toml({"camera": {key: 1.0}})
            with self.assertRaises(ValueError):
                scene_toml.scene_toml({key: {"angle": 1.0}})

    def test_pattern_characters_in_paths_are_literal(self):
        self.assertEqual(scene_toml.escape_pattern("/tmp/run#2/[a]*?/mesh"),
                         "/tmp/run\\#2/\\[a]\\*\\?/mesh")


class FindingToonwater(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.environ["PATH"]

    def tearDown(self):
        os.environ["PATH"] = self.path
        self.tmp.cleanup()

    def test_preference_must_be_an_executable_file(self):
        not_executable = os.path.join(self.tmp.name, "toonwater")
        open(not_executable, "w").close()
        for preference in [not_executable, self.tmp.name, os.path.join(self.tmp.name, "none")]:
            with self.assertRaisesRegex(job.ToonwaterNotFound, "is not an executable file"):
                job.find_toonwater(preference)
        self.assertEqual(job.find_toonwater(TOONWATER), os.path.abspath(TOONWATER))

    def test_path_is_searched_without_a_preference(self):
        os.environ["PATH"] = self.tmp.name
        with self.assertRaisesRegex(job.ToonwaterNotFound, "toonwater is not on PATH"):
            job.find_toonwater("")
        os.environ["PATH"] = os.path.dirname(os.path.abspath(TOONWATER))
        self.assertEqual(os.path.realpath(job.find_toonwater("")), os.path.realpath(TOONWATER))


def run(steps, cwd):
    j = job.ToonwaterJob(steps, cwd, os.path.join(cwd, "toonwater.log"))
    j.start()
    deadline = time.monotonic() + 120
    state = j.poll()
    while not state.finished and time.monotonic() < deadline:
        time.sleep(0.05)
        state = j.poll()
    return state


class RunningToonwater(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_an_error_is_one_line_with_the_log(self):
        state = run([job.Step("povgen", [TOONWATER, "povgen", "--water", "missing_0001.obj",
                                         "--out", "scene"]),
                     job.Step("render", [TOONWATER, "render", "scene"])], self.dir)
        self.assertTrue(state.finished)
        self.assertEqual(len(state.errors), 1, state.errors)
        log = os.path.join(self.dir, "toonwater.log")
        self.assertRegex(state.errors[0], r"^toonwater povgen: .*missing_0001\.obj.*\(log: %s\)$"
                         % log.replace(".", r"\."))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "scene")))
        with open(log) as f:
            self.assertNotIn("toonwater render", f.read())  # the second step never started

    def test_steps_run_in_order(self):
        steps = [job.Step("simulate", [TOONWATER, "simulate", "drop", "--frames", "3",
                                       "--out", "sim"]),
                 job.Step("povgen", [TOONWATER, "povgen", "--water", "sim/water_####.obj",
                                     "--set", "render.width=32", "--set", "render.height=24",
                                     "--set", "render.quality=draft", "--out", "scene"])]
        state = run(steps, self.dir)
        self.assertEqual((state.finished, state.errors, state.fraction), (True, [], 1.0))
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "scene", "scene.pov")))
        with open(os.path.join(self.dir, "toonwater.log")) as f:
            log = f.read()
        self.assertLess(log.index("simulate"), log.index("$ %s povgen" % TOONWATER))

    def test_a_program_that_cannot_start_is_an_error(self):
        not_executable = os.path.join(self.dir, "toonwater")
        open(not_executable, "w").close()
        state = run([job.Step("povgen", [not_executable, "povgen"])], self.dir)
        self.assertTrue(state.finished)
        self.assertEqual(len(state.errors), 1)
        self.assertRegex(state.errors[0], r"^toonwater povgen: could not start .*: Permission "
                                          r"denied \(log: .*toonwater\.log\)$")

    def test_exit_code_without_an_error_line_is_named(self):
        # toonwater ended by a signal writes no error line: its exit is reported instead.
        state = run([job.Step("povgen", ["sh", "-c", "kill -KILL $$"])], self.dir)
        self.assertEqual(len(state.errors), 1)
        self.assertIn("ended by signal 9", state.errors[0])


if __name__ == "__main__":
    unittest.main(verbosity=2)
