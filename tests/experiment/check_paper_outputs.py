#!/usr/bin/python3
"""End-to-end check of peg-paper: run it with a tiny budget and verify that every documented output file
exists with its documented columns (docs/results.md), that two runs with the same seed give identical
result files, and that bad input exits with status 2 and writes nothing.

usage: check_paper_outputs.py PEG_PAPER_BINARY SOURCE_DIR WORK_DIR
"""
import csv
import json
import os
import re
import shutil
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import check, run as run_program, verdict  # noqa: E402

EPISODE = ["outcome", "captured", "capture_time_s", "episode_time_s", "final_distance_m", "pursuer_path_m",
           "evader_path_m", "collisions", "evader_pinned_fraction", "pursuer_pinned_fraction", "pursuer_return",
           "evader_return"]
RUNS = ["scenario", "algorithm", "repeat", "seed", "train_captures"] + EPISODE
CURVES = ["scenario", "algorithm", "repeat", "episode", "pool_opponent"] + EPISODE
TRAJ = ["t", "pursuer_0_x", "pursuer_0_y", "pursuer_0_z", "evader_0_x", "evader_0_y", "evader_0_z", "pursuer_0_alpha",
        "pursuer_0_theta", "evader_0_alpha", "evader_0_theta", "distance"] + [
            f"{a}_{c}" for a in ("pursuer_0", "evader_0") for c in (
                "d_target", "target_az", "target_el", "d_obstacle", "obstacle_az", "obstacle_el", "d_alpha",
                "d_theta", "reward", "pinned")] + [
            f"{a}_{c}" for a in ("pursuer_0", "evader_0") for c in ("active", "hit", "captured")]
FIGURES = ["trajectories.png", "comparison.png", "learning.png", "apollonius.png"]
DETERMINISTIC = ["runs.csv", "learning_curves.csv", "summary.json", "config.json"]


def header(path):
    with open(path, newline="") as f:
        return next(csv.reader(f))


def documented_names(path):
    """Every name written in backticks in a Markdown file, lists like `a, b, c` split into their items."""
    names = set()
    for span in re.findall(r"`([^`]+)`", open(path).read()):
        for item in span.split(","):
            names.add(item.strip())
    return names


def run(binary, out, *extra):
    cmd = [binary, "--out", out, "--repeats", "2", "--episodes", "3", "--plain-progress", "--no-cache", *extra]
    if "--map" not in extra:
        cmd += ["--map", "maps/paper.yaml"]
    return run_program(cmd)


def check_trailing_mean(source):
    """learning.png's average: the last `window` finite values, skipping the gaps of opponent-pool episodes."""
    sys.path.insert(0, os.path.join(source, "tools"))
    import numpy as np
    import plot_paper
    nan = float("nan")
    got = plot_paper.trailing_mean(np.array([[1.0, 2.0, 3.0, 4.0], [nan, 1.0, nan, 3.0]]), 2)
    check(got[0].tolist() == [1.0, 1.5, 2.5, 3.5], f"trailing mean without gaps: {got[0].tolist()}")
    check(np.isnan(got[1][0]) and got[1][1:].tolist() == [1.0, 1.0, 2.0], f"trailing mean over gaps: {got[1].tolist()}")


def main():
    binary, source, work = sys.argv[1:4]
    os.chdir(source)
    check_trailing_mean(source)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    a, b = os.path.join(work, "a"), os.path.join(work, "b")

    r = run(binary, a)
    check(r.returncode == 0, f"peg-paper exit status {r.returncode}: {r.stderr[-2000:]}")
    check("scenario" in r.stdout and "paired comparisons" in r.stdout, "summary table on stdout")
    check(header(os.path.join(a, "runs.csv")) == RUNS, "runs.csv columns")
    check(header(os.path.join(a, "learning_curves.csv")) == CURVES, "learning_curves.csv columns")
    with open(os.path.join(a, "runs.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 4 * 3 * 2, f"runs.csv has {len(rows)} rows, expected 24")
    with open(os.path.join(a, "learning_curves.csv")) as f:
        check(sum(1 for _ in f) == 1 + 24 * 3, "learning_curves.csv has one row per training episode")
    for s in ("S1", "S2", "S3", "S4"):
        for alg in ("peg3d", "baseline", "paper"):
            t = os.path.join(a, "trajectories", f"{s}_{alg}.csv")
            check(os.path.exists(t) and header(t) == TRAJ, f"trajectory {s}_{alg} columns")
            for role in ("pursuer", "evader"):
                p = os.path.join(a, "policies", f"{s}_{alg}_{role}.json")
                check(os.path.exists(p) and json.load(open(p))["format"] == "peg3d-policy", f"policy {s}_{alg}_{role}")
    summary = json.load(open(os.path.join(a, "summary.json")))
    for s in ("S1", "S2", "S3", "S4"):
        algs = summary["scenarios"][s]["algorithms"]
        for alg in ("peg3d", "baseline", "paper"):
            for key in ("capture_rate", "capture_time_s", "pursuer_path_m", "evader_pinned_fraction"):
                check(key in algs[alg], f"summary {s} {alg} {key}")
        check(len(summary["scenarios"][s]["comparisons"]) == 6, f"summary {s} comparisons")
    for name in ("config.json", "map.json", "apollonius.json", "timing.json"):
        check(os.path.exists(os.path.join(a, name)), name)
    for fig in FIGURES:
        path = os.path.join(a, fig)
        check(os.path.exists(path) and os.path.getsize(path) > 10000, f"figure {fig}")
    documented = documented_names(os.path.join(source, "docs", "results.md"))
    for col in RUNS + CURVES + TRAJ:
        # Per-agent trajectory columns are documented once for an agent `a`: `a_d_target` stands for
        # pursuer_0_d_target and evader_0_d_target.
        generic = re.sub(r"^(pursuer|evader)_[0-9]+_", "a_", col)
        check(col in documented or generic in documented, f"column {col} documented in docs/results.md")

    r = run(binary, b, "--no-plots", "--threads", "1")
    check(r.returncode == 0, "second run")
    for name in DETERMINISTIC:
        same = open(os.path.join(a, name), "rb").read() == open(os.path.join(b, name), "rb").read()
        check(same, f"{name} identical for the same seed with 2 threads and 1 thread")

    # The opponent pool's episodes are told apart from co-learning ones, so that learning.png can leave them out.
    with open(os.path.join(a, "learning_curves.csv")) as f:
        check(all(row["pool_opponent"] == "" for row in csv.DictReader(f)), "co-learning: no pool opponent")
    pooled = os.path.join(work, "pooled")
    r = run(binary, pooled, "--algorithms", "robust", "--no-plots")
    check(r.returncode == 0, f"robust run exit status {r.returncode}: {r.stderr[-2000:]}")
    opponents = []
    if r.returncode == 0:
        with open(os.path.join(pooled, "learning_curves.csv")) as f:
            opponents = [row["pool_opponent"] for row in csv.DictReader(f)]
    classic = {"pure-pursuit", "pn", "apollonius", "flee", "flee-apollonius", "random"}
    check(len(opponents) == 4 * 2 * 3, f"robust: {len(opponents)} training episodes, expected 24")
    check("" in opponents and set(opponents) - {""} and set(opponents) <= classic | {""},
          f"robust: pool opponents {sorted(set(opponents))}")

    bad = os.path.join(work, "bad")
    for args in (["--set", "pursuer.speed=-1"], ["--set", "pursuer.nosuchfield=1"], ["--repeats", "0"],
                 ["--algorithms", "peg3d,unknown"], ["--map", "tests/data/does-not-exist.yaml"]):
        r = run(binary, bad, *args)
        check(r.returncode == 2, f"{args}: exit status {r.returncode}, expected 2")
        check(r.stderr.startswith("error:"), f"{args}: 'error: ...' on stderr, got {r.stderr[:200]!r}")
        check(not os.path.exists(bad) or not os.listdir(bad), f"{args}: no output written")

    return verdict()


if __name__ == "__main__":
    sys.exit(main())
