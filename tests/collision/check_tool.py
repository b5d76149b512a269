#!/usr/bin/python3
"""The collision-regression tool must be able to fail: moving one obstacle of a case's map by 1 cm, or changing
one command of its motion, makes `peg-collide run` exit 1 with a diff naming the changed event; restoring it
passes again. Also: `new` makes a case that passes, `--update` rewrites a differing golden log, and bad input
(no golden log, a broken case, a broken motion file) exits 2.

usage: check_tool.py PEG_COLLIDE SUITE_DIR WORK_DIR
"""
import os
import shutil
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import check, run as run_program, verdict  # noqa: E402


def run(*args):
    return run_program(list(args))


def main():
    tool, suite, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copytree(os.path.join(suite, "maps"), os.path.join(work, "maps"))
    case = os.path.join(work, "straight-sphere")
    shutil.copytree(os.path.join(suite, "straight-sphere"), case)
    map_file = os.path.join(work, "maps", "shapes.yaml")
    original_map = open(map_file).read()

    r = run(tool, "run", case)
    check(r.returncode == 0 and "ok   straight-sphere" in r.stdout, f"the copied case passes: {r.stdout}{r.stderr}")

    # Sphere 0 moved 1 cm away from the agent (towards it would overlap scenario start-touching's start):
    # the contact comes 1 cm (9.1 ms at 1.1 m/s) later.
    open(map_file, "w").write(original_map.replace("center: [15, 10, 10], radius: 1}", "center: [15.01, 10, 10], radius: 1}"))
    r = run(tool, "run", case)
    check(r.returncode == 1, f"a moved obstacle fails the case (status {r.returncode}): {r.stdout}{r.stderr}")
    check("straight-sphere: event 1: time 7.954545 s -> 7.963636 s" in r.stdout, f"the diff names the event's time: {r.stdout}")
    check("straight-sphere: event 1: point (14.000000, 10.000000, 10.000000) -> (14.010000" in r.stdout, f"and its point: {r.stdout}")
    open(map_file, "w").write(original_map)
    r = run(tool, "run", case)
    check(r.returncode == 0, f"restored, it passes again: {r.stdout}")

    # One command changed: a turn of 2 degrees a step from 4 s on misses the sphere.
    case_file = os.path.join(case, "case.yaml")
    original_case = open(case_file).read()
    open(case_file, "w").write(original_case.replace("commands: [[0, 0, 0]]", "commands: [[0, 0, 0], [4, 2, 0]]"))
    r = run(tool, "run", case)
    check(r.returncode == 1, f"a changed command fails the case: {r.stdout}")
    check("straight-sphere: event 1: pursuer_0 hit sphere:0 at 7.954545 s -> (none)" in r.stdout, f"the diff names the vanished event: {r.stdout}")
    r = run(tool, "run", "--update", case)
    check(r.returncode == 0 and "updated" in r.stdout, "--update rewrites the golden log")
    check(run(tool, "run", case).returncode == 0, "and the case passes with it")
    open(case_file, "w").write(original_case)
    check(run(tool, "run", case).returncode == 1, "the updated golden log no longer fits the original motion")
    check(run(tool, "record", case).returncode == 0 and run(tool, "run", case).returncode == 0, "record restores it")

    # A case from a user's own map and motion.
    motion = os.path.join(work, "dive.commands")
    open(motion, "w").write("# time_s d_alpha_deg d_theta_deg\n0 0 0\n2 0 5\n")
    made = os.path.join(work, "my-suite", "dive")
    r = run(tool, "new", "--map", map_file, "--motion", motion, "--out", made, "--scenario", "toward-sphere",
            "--set", "pursuer.guard.enabled=false", "--set", "pursuer.steering.polar_margin=0")
    check(r.returncode == 0 and os.path.exists(os.path.join(made, "golden.log")), f"new records a case: {r.stdout}{r.stderr}")
    r = run(tool, "run", os.path.join(work, "my-suite"))
    check(r.returncode == 0 and "ok   dive" in r.stdout, f"a folder of cases runs: {r.stdout}{r.stderr}")

    # Bad input: exit 2, a message naming the file.
    no_golden = os.path.join(work, "no-golden")
    shutil.copytree(case, no_golden)
    os.remove(os.path.join(no_golden, "golden.log"))
    bad_motion = os.path.join(work, "bad.commands")
    open(bad_motion, "w").write("0 0 0\n1 x 0\n")
    broken = os.path.join(work, "broken")
    os.makedirs(broken)
    open(os.path.join(broken, "case.yaml"), "w").write("map: ../maps/shapes.yaml\ncolour: blue\n")
    for args, named in ((["run", no_golden], "golden.log"), (["run", broken], "colour"),
                        (["new", "--map", map_file, "--motion", bad_motion, "--out", os.path.join(work, "x")], "bad.commands:2")):
        r = run(tool, *args)
        check(r.returncode == 2 and named in r.stderr, f"{args}: status {r.returncode}, message {r.stderr!r}")
    check(not os.path.exists(os.path.join(work, "x")), "a refused new case leaves nothing behind")
    # Refused only when played (the map has no such scenario): the half-made case is removed too.
    r = run(tool, "new", "--map", map_file, "--motion", motion, "--out", os.path.join(work, "y"), "--scenario", "nowhere")
    check(r.returncode == 2 and "nowhere" in r.stderr, f"an unknown scenario: status {r.returncode}, {r.stderr!r}")
    check(not os.path.exists(os.path.join(work, "y")), "a case that cannot be recorded leaves nothing behind")

    return verdict()


if __name__ == "__main__":
    sys.exit(main())
