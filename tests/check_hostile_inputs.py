#!/usr/bin/env python3
"""Every broken or hostile input, through the programs a user runs: exit status 2, a message on stderr that
starts with "error:" and names the file, within 10 s of processor time (user and system, the import's child
included; 120 s of wall clock count as a hang), peak memory under 1 GB, and no output written.

  meshes    tests/data/meshes/hostile/*   each as the terrain of a small map, through peg-matchup
  maps      tests/data/maps/broken/*.yaml and tests/data/maps/hostile/*.yaml (maps that load but would build or
            simulate too much: aliases, generators, motion over its budget) through peg-map check
  heavy     tests/data/maps/heavy/*.yaml, valid maps at the limits, through peg-map check: exit status 0, within
            10 s, under 1 GB
  configs   tests/data/configs/broken/*.json through peg-matchup --config
  policies  broken policy files made here (and a FIFO, a directory, /dev/zero) through peg-matchup

Usage: check_hostile_inputs.py BIN_DIR SOURCE_DIR WORK_DIR [--sanitized]

The limits are the Release build's. With --sanitized (an ASan/UBSan build, 2-3 times slower) the time limit is
doubled: on a quiet machine peg-map takes 2.6 s on heavy/generator_at_the_limit.yaml in Release and 5.7 s
sanitized. Processor time, not wall clock, is what is limited: on a loaded machine a sanitized peg-map took
13-17 s of wall clock for those 5 s of work.
"""

import json
import os
import resource
import shutil
import subprocess
import sys
import time

failures = []
LIMIT_SECONDS = 10.0        # processor time of one program
WALL_LIMIT_SECONDS = 120    # a program still running then is stopped and counted as hanging
LIMIT_KB = 1024 * 1024  # 1 GiB, as ru_maxrss counts


def run(cmd, named, out_dir, expect_error=True):
    """Runs cmd and checks the contract for an input error that names `named` (or, with expect_error false, that
    it succeeds within the same time and memory)."""
    shutil.rmtree(out_dir, ignore_errors=True)
    start = time.monotonic()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    try:
        _, err = p.communicate(timeout=WALL_LIMIT_SECONDS)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        failures.append(f"{named}: still running after {WALL_LIMIT_SECONDS} s")
        return
    wall = time.monotonic() - start
    # The limit is on the processor time the program used (user + system, its children's included): what a
    # hostile input can make it do, the same on a quiet machine and on a loaded one, where the wall clock of a
    # sanitized build ran past it (13-17 s for 5 s of work). A program that hangs without working is caught by
    # the wall-clock limit above.
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    seconds = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    # wait4 has been done by communicate; the rusage of the whole tree comes from RUSAGE_CHILDREN's maximum.
    err = err.decode(errors="replace")
    what = f"{os.path.basename(cmd[0])} on {named}"
    if not expect_error:
        if p.returncode != 0:
            failures.append(f"{what}: exit status {p.returncode}, expected 0: {err[-400:]}")
        if seconds > LIMIT_SECONDS:
            failures.append(f"{what}: took {seconds:.1f} s of processor time ({wall:.1f} s)")
        return
    if p.returncode != 2:
        failures.append(f"{what}: exit status {p.returncode}, expected 2: {err[-400:]}")
    if not err.startswith("error:") or os.path.basename(named) not in err:
        failures.append(f"{what}: the message does not name the file: {err[:300]!r}")
    if seconds > LIMIT_SECONDS:
        failures.append(f"{what}: took {seconds:.1f} s of processor time ({wall:.1f} s)")
    if os.path.exists(out_dir):
        failures.append(f"{what}: wrote {out_dir}")


def main():
    global LIMIT_SECONDS
    bin_dir, source, work = sys.argv[1:4]
    if "--sanitized" in sys.argv[4:]:
        LIMIT_SECONDS *= 2
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    matchup, peg_map = os.path.join(bin_dir, "peg-matchup"), os.path.join(bin_dir, "peg-map")
    out = os.path.join(work, "out")
    quick = ["--repeats", "1", "--episodes", "2", "--plain-progress", "--no-cache", "--out", out]
    counts = {}

    hostile = os.path.join(source, "tests", "data", "meshes", "hostile")
    for name in sorted(os.listdir(hostile)):
        if name == "expect.txt":
            continue
        map_file = os.path.join(work, f"terrain_{name}.yaml")
        with open(map_file, "w") as f:
            f.write("arena: {size: [10, 10, 10]}\n"
                    f"terrain:\n  - file: {os.path.join(hostile, name)}\n"
                    "start:\n  pursuer: {position: [1, 1, 9]}\n  evader: {position: [9, 9, 9]}\n")
        run([matchup, "--map", map_file, *quick], name, out)
        counts["meshes"] = counts.get("meshes", 0) + 1

    for folder in ("broken", "hostile"):
        maps = os.path.join(source, "tests", "data", "maps", folder)
        for name in sorted(os.listdir(maps)):
            run([peg_map, "check", os.path.join(maps, name), "--no-cache"], name, out)
            counts["maps"] = counts.get("maps", 0) + 1
    heavy = os.path.join(source, "tests", "data", "maps", "heavy")
    for name in sorted(os.listdir(heavy)):
        run([peg_map, "check", os.path.join(heavy, name), "--no-cache"], name, out, expect_error=False)
        counts["heavy"] = counts.get("heavy", 0) + 1

    configs = os.path.join(source, "tests", "data", "configs", "broken")
    for name in sorted(n for n in os.listdir(configs) if n.endswith(".json")):
        run([matchup, "--config", os.path.join(configs, name), *quick], name, out)
        counts["configs"] = counts.get("configs", 0) + 1

    # Amplification: 4 MB of empty per-pursuer entries (10^6) once grew past 4 GiB before any run; refused at once.
    amplified = os.path.join(work, "million_pursuers.json")
    with open(amplified, "w") as f:
        f.write('{"pursuers": [' + ",".join(["{}"] * 1000000) + "]}")
    run([matchup, "--config", amplified, *quick], "million_pursuers.json", out)
    counts["configs"] += 1

    policies = os.path.join(work, "policies")
    os.makedirs(policies)
    cases = {
        "deep.json": "[" * 100000 + "]" * 100000,
        "truncated.json": '{"format": "peg3d-policy", "version": 1, "role": "pursuer"',
        "wrong_type.json": json.dumps({"format": "peg3d-policy", "version": "one"}),
        "not_a_policy.json": json.dumps({"hello": "world"}),
        "huge_string.json": json.dumps({"format": "peg3d-policy", "version": 1, "role": "x" * 1000000}),
        "nan.json": '{"format": "peg3d-policy", "version": NaN}',
        "empty.json": "",
        # Loads (every weight finite), but the network overflows to NaN on its first input: step() refuses it.
        "overflowing_mlp.json": json.dumps({
            "format": "peg3d-mlp", "version": 1, "role": "pursuer", "inputs": 20, "action_bound": 0.4,
            "input_mean": [0.0] * 20, "input_std": [0.01] * 20,
            "layers": [{"weights": [[1e308 if i % 2 == 0 else -1e308 for i in range(20)]] * 2, "bias": [0.0, 0.0]}]}),
    }
    for name, text in cases.items():
        with open(os.path.join(policies, name), "w") as f:
            f.write(text)
    fifo = os.path.join(policies, "fifo.json")
    os.mkfifo(fifo)
    os.makedirs(os.path.join(policies, "folder.json"))
    for name in [*cases, "fifo.json", "folder.json"]:
        run([matchup, "--pursuer-policy", os.path.join(policies, name), *quick], name, out)
        counts["policies"] = counts.get("policies", 0) + 1
    run([matchup, "--pursuer-policy", "/dev/zero", *quick], "/dev/zero", out)

    # --save-maps checks nothing later than the rest: with a broken map it leaves no folder, and an unusable --out
    # is refused as it is without it.
    broken = os.path.join(source, "tests", "data", "maps", "broken")
    first_broken = sorted(os.listdir(broken))[0]
    run([matchup, "--map", os.path.join(broken, first_broken), "--save-maps", "all", *quick], first_broken, out)
    blocker = os.path.join(work, "a_plain_file")
    with open(blocker, "w") as f:
        f.write("not a folder\n")
    under_file = os.path.join(blocker, "out")
    run([matchup, "--save-maps", "all", "--repeats", "1", "--episodes", "2", "--plain-progress", "--no-cache",
         "--out", under_file], "a_plain_file", under_file)
    counts["flags"] = 2

    # An own map whose arena OctoMap's 16-bit keys do not reach (more than 8192 m from the origin at 0.25 m), or
    # straddle: refused before any game, naming the field (the world's own octree, at 1 m, reaches them; the
    # game played on with an empty map, or ended with exit 1).
    own_map = os.path.join(work, "own_map.json")
    with open(own_map, "w") as f:
        json.dump({"pursuer": {"lidar": {"azimuth_rays": 8, "elevation_rays": 1}, "map": {"enabled": True}}}, f)
    for name, low in (("far_arena.yaml", 9000), ("straddling_arena.yaml", 8180)):
        far = os.path.join(work, name)
        with open(far, "w") as f:
            f.write(f"arena: {{min: [{low}, 0, 0], size: [20, 20, 10]}}\noccupancy: {{resolution: 1.0}}\n"
                    f"start:\n  pursuer: {{position: [{low + 1}, 1, 5]}}\n  evader: {{position: [{low + 15}, 15, 5]}}\n")
        run([matchup, "--map", far, "--config", own_map, *quick], "pursuer.map.resolution", out)
        counts["flags"] += 1

    import resource
    peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    if peak_kb > LIMIT_KB:
        failures.append(f"the largest process (import children included) peaked at {peak_kb / 1024:.0f} MB")
    print(f"checked {counts}; peak memory of any process {peak_kb / 1024:.0f} MB")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
