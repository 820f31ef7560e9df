# Running toonwater's commands one after the other as child processes: progress read from
# their log, errors as one line each, and a cancel that leaves no process behind.
# Pure Python: no bpy, so the operator's modal loop and the tests drive the same code.
import os
import re
import shlex
import shutil
import signal
import subprocess
import time

# What each of toonwater's exit codes means (cli/exit_codes.hpp, README "Exit codes").
EXIT_MEANINGS = {
    1: "internal error",
    2: "bad input",
    3: "an output could not be written",
    4: "interrupted",
    5: "POV-Ray failed on at least one frame",
    6: "incomplete installation",
}
_PROGRESS = re.compile(r"^(povgen|render): (survey, )?frame (\d+)/(\d+)")
_ERROR = re.compile(r"^toonwater: error: (.*)$")
# How long a cancelled toonwater may take to end its POV-Ray children and remove its
# temporaries before its whole process group is killed.
CANCEL_GRACE_SECONDS = 20.0


class ToonwaterNotFound(Exception):
    pass


def find_toonwater(preference=""):
    """The toonwater program: the add-on preference's path when set, else toonwater on PATH."""
    if preference:
        path = os.path.abspath(os.path.expanduser(preference))
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise ToonwaterNotFound("the toonwater program set in the add-on's preferences, %s, "
                                "is not an executable file" % path)
    found = shutil.which("toonwater")
    if not found:
        raise ToonwaterNotFound("toonwater is not on PATH: install it, or set the program's "
                                "path in Preferences > Add-ons > Toon water")
    return found


class Step:
    def __init__(self, title, argv, prepare=None):
        self.title = title  # "povgen", "render"
        self.argv = argv
        self.prepare = prepare  # called just before the step starts, once the last succeeded


class JobState:
    def __init__(self, finished, fraction, text, errors, cancelled):
        self.finished = finished
        self.fraction = fraction  # 0..1 over all steps
        self.text = text          # one line for the status bar
        self.errors = errors      # one line each, ending with the log's path
        self.cancelled = cancelled


class ToonwaterJob:
    """Runs `steps` in `cwd`, each after the last succeeded, with their output in `log_path`."""

    def __init__(self, steps, cwd, log_path):
        self.steps = steps
        self.cwd = cwd
        self.log_path = log_path
        self._index = -1
        self._process = None
        self._log = None
        self._read_offset = 0
        self._step_fraction = 0.0
        self._has_survey = False  # povgen's survey pass ran (two passes to show)
        self._text = "starting"
        self._errors = []
        self._error_lines = []
        self._cancelled = False
        self._finished = False

    def start(self):
        self._log = open(self.log_path, "wb")
        self._start_next()

    def _start_next(self):
        self._index += 1
        self._step_fraction = 0.0
        self._error_lines = []
        step = self.steps[self._index]
        if step.prepare:
            try:
                step.prepare()
            except OSError as e:
                self._errors = ["toonwater %s: %s (log: %s)" % (step.title, e, self.log_path)]
                self._finish()
                return
        self._log.write(("$ " + shlex.join(step.argv) + "\n").encode())
        self._log.flush()
        try:
            # Its own session: a cancel can reach every process it started (POV-Ray included).
            self._process = subprocess.Popen(step.argv, cwd=self.cwd, stdin=subprocess.DEVNULL,
                                             stdout=self._log, stderr=subprocess.STDOUT,
                                             start_new_session=True)
        except OSError as e:
            self._errors = ["toonwater %s: could not start %s: %s (log: %s)"
                            % (step.title, step.argv[0], e.strerror, self.log_path)]
            self._finish()
            return
        self._text = step.title + ": started"

    def _read_log(self):
        with open(self.log_path, "rb") as f:
            f.seek(self._read_offset)
            chunk = f.read()
        complete = chunk.rfind(b"\n") + 1  # a line still being written is read next time
        self._read_offset += complete
        for line in chunk[:complete].decode("utf-8", "replace").splitlines():
            progress = _PROGRESS.match(line)
            if progress:
                command, survey, done, total = progress.groups()
                self._has_survey = self._has_survey or bool(survey)
                # povgen's survey pass and frame pass are each half of its step.
                part = int(done) / max(1, int(total))
                if command == "povgen" and self._has_survey:
                    part = 0.5 * part if survey else 0.5 + 0.5 * part
                self._step_fraction = part
                self._text = "%s: %sframe %s/%s" % (command, survey or "", done, total)
            error = _ERROR.match(line)
            if error:
                self._error_lines.append(error.group(1))

    def poll(self):
        """Advances the job; call it until the state says finished."""
        if not self._finished:
            self._read_log()
            code = self._process.poll()
            if code is not None:
                self._read_log()
                self._step_done(code)
        n = len(self.steps)
        fraction = 1.0 if self._finished and not self._errors else \
            (max(0, self._index) + self._step_fraction) / n
        return JobState(self._finished, fraction, self._text, list(self._errors),
                        self._cancelled)

    def _step_done(self, code):
        step = self.steps[self._index]
        if code == 0 and not self._cancelled:
            if self._index + 1 < len(self.steps):
                self._start_next()
                return
            self._text = "done"
        elif not self._cancelled:
            meaning = EXIT_MEANINGS.get(code, "ended by signal %d" % -code if code < 0 else "")
            lines = self._error_lines or ["%s failed (exit %d: %s)" % (step.title, code, meaning)]
            self._errors = ["toonwater %s: %s (log: %s)" % (step.title, line, self.log_path)
                            for line in lines]
        self._finish()

    def _finish(self):
        self._finished = True
        self._log.close()

    def cancel(self):
        """Stops the running command with SIGTERM, which toonwater handles as it does Ctrl+C,
        and waits until it and every process it started are gone; toonwater leaves its outputs
        as they were (exit 4)."""
        if self._finished:
            return
        self._cancelled = True
        self._text = "cancelled"
        group = self._process.pid  # the session leader's id is its group's id
        try:
            self._process.send_signal(signal.SIGTERM)
            self._process.wait(timeout=CANCEL_GRACE_SECONDS)
        except subprocess.TimeoutExpired:
            pass
        deadline = time.monotonic() + CANCEL_GRACE_SECONDS
        while _group_alive(group) and time.monotonic() < deadline:
            time.sleep(0.05)
        if _group_alive(group):
            os.killpg(group, signal.SIGKILL)
        self._process.wait()
        self._read_log()
        self._finish()


def _group_alive(group):
    try:
        os.killpg(group, 0)
        return True
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
