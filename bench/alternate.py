#!/usr/bin/env python3
"""Whole commands timed side by side: the benchmarks' one way of comparing two or more programs.

    bench/alternate.py [--rounds N] [--warm-ups N] [--rotate] [--sum LABEL=NAME+NAME...]
                       NAME=COMMAND [NAME=COMMAND ...]

Each COMMAND (shell text, run by bash) runs WARM_UPS times (1 unless given; more where a program
fills caches of its own over its first runs, as Blender does), then ROUNDS times in turn with the
others, A B C A B C ..., so that a change in the machine's load falls on all of them alike.
With --rotate each round starts one command later (A B C, B C A, C A B, ...): a program run
just after another can be slowed by it (a build of toonwater run just after MeshLab took 20-40
ms more than the same build run after the other), and without rotation the same command would
always pay for it; not for commands that need the one before them (povgen, then its render).
It prints, per command, the median (min–max) of its wall and CPU (user + system, its children's
included) seconds, and the median (min–max) of the rounds' ratios to the first command, the
reference: a ratio of each round's own times, not of the medians. `--sum LABEL=A+B` adds a row
for commands that together make one job (povgen and render), its time each round their sum.
A command that fails stops the comparison: its last lines and exit status 1. The commands' own
output goes to NAME.log in a temporary directory, or in KEEP_LOGS when that is set.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time


def fail(message):
    print(f"alternate: error: {message}", file=sys.stderr)
    sys.exit(1)


def parse_pairs(texts, what):
    pairs = []
    for text in texts:
        name, sep, value = text.partition("=")
        if not sep or not name or not value:
            fail(f"{what} is NAME=VALUE, not '{text}'")
        pairs.append((name, value))
    return pairs


def run_once(name, command, log_dir):
    """Wall and CPU seconds of one run of the command."""
    log_path = os.path.join(log_dir, f"{name}.log".replace("/", "_"))
    with open(log_path, "wb") as log:
        start = time.perf_counter()
        process = subprocess.Popen(["bash", "-c", command], stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - start
    # Reaped here, with its resource usage: Popen must not wait for it again.
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        with open(log_path, errors="replace") as log:
            tail = log.readlines()[-5:]
        sys.stderr.writelines(tail)
        fail(f"{name} failed (exit {process.returncode}; log {log_path}): {command}")
    return wall, usage.ru_utime + usage.ru_stime


def summary(values, digits):
    return (f"{statistics.median(values):.{digits}f} "
            f"({min(values):.{digits}f}–{max(values):.{digits}f})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--warm-ups", type=int, default=1)
    parser.add_argument("--rotate", action="store_true")
    parser.add_argument("--sum", action="append", default=[], metavar="LABEL=NAME+NAME")
    parser.add_argument("commands", nargs="+", metavar="NAME=COMMAND")
    args = parser.parse_args()
    if not 1 <= args.rounds <= 999:
        fail(f"--rounds is 1-999, not {args.rounds}")
    if not 0 <= args.warm_ups <= 99:
        fail(f"--warm-ups is 0-99, not {args.warm_ups}")
    commands = parse_pairs(args.commands, "a command")
    names = [name for name, _ in commands]
    if len(set(names)) != len(names):
        fail("two commands have the same name")
    sums = []
    for label, parts in parse_pairs(args.sum, "--sum"):
        members = parts.split("+")
        unknown = [m for m in members if m not in names]
        if unknown:
            fail(f"--sum {label}: no command named {', '.join(unknown)}")
        sums.append((label, members))

    load_before = os.getloadavg()[0]  # the machine's, before the commands add their own
    log_dir = os.environ.get("KEEP_LOGS") or tempfile.mkdtemp(prefix="alternate-")
    os.makedirs(log_dir, exist_ok=True)
    for _ in range(args.warm_ups):
        for name, command in commands:
            run_once(name, command, log_dir)
    times = {name: [] for name in names}
    for r in range(args.rounds):
        first = r % len(commands) if args.rotate else 0
        for name, command in commands[first:] + commands[:first]:
            times[name].append(run_once(name, command, log_dir))
    for label, members in sums:
        times[label] = [tuple(sum(times[m][r][k] for m in members) for k in (0, 1))
                        for r in range(args.rounds)]

    reference = names[0]
    warm_ups = "a warm-up" if args.warm_ups == 1 else f"{args.warm_ups} warm-ups"
    order = ", each starting one command later" if args.rotate else ""
    print(f"{args.rounds} rounds{order} after {warm_ups} each, {os.cpu_count()} cores, load "
          f"{load_before:.1f} before them; medians (min–max) in seconds; ratios to {reference}, "
          "round by round")
    print("| command | wall | CPU | wall ratio | CPU ratio |")
    print("|---|---:|---:|---:|---:|")
    for name, runs in times.items():
        walls, cpus = [w for w, _ in runs], [c for _, c in runs]
        ratios = ["", ""]
        if name != reference:
            ratios = [summary([a[k] / b[k] for a, b in zip(runs, times[reference])], 3)
                      if all(b[k] > 0 for b in times[reference]) else "no time to divide by"
                      for k in (0, 1)]
        print(f"| {name} | {summary(walls, 3)} | {summary(cpus, 3)} | {ratios[0]} | {ratios[1]} |")


if __name__ == "__main__":
    main()
