#!/usr/bin/env python3
"""Capture rate (Wilson 95 % interval) and capture time of C++-side pursuers against C++-side evaders, one
episode per game of a vector env, every start of the map's scenarios in turn with random headings:

    PYTHONPATH=build/python /usr/bin/python3 examples/evaluate_pursuers.py --episodes 200 \
        --pursuer pure-pursuit --pursuer tests/data/policies/ppo_pursuer.json --evader flee --evader flee-apollonius

Prints one JSON line per (map, pursuer, evader).
"""

import argparse
import json
import math

import numpy as np

import peg3d


def wilson(k, n, z=1.96):
    if n == 0:
        return (float("nan"), float("nan"))
    p = k / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (c - h, c + h)


def evaluate(map_, pursuer, evader, episodes, seed, threads):
    v = peg3d.vector_env(map=map_, num_envs=episodes, threads=threads, neighbours=0, seed=seed,
                         opponents={"pursuer": pursuer, "evader": evader}, set={"initial_heading": "random"})
    v.reset(seed=seed)
    finished = np.zeros(episodes, dtype=bool)
    outcome, times = [None] * episodes, np.zeros(episodes)
    while not finished.all():
        _, _, term, trunc, info = v.step({})
        ended = (term["pursuer"][:, 0] | trunc["pursuer"][:, 0]) & ~finished
        for g in np.flatnonzero(ended):
            gi = v._batch.game_info(int(g))
            outcome[g], times[g] = gi["outcome"], gi["time"]
        finished |= ended
    captured = np.array([o == "capture" for o in outcome])
    k = int(captured.sum())
    lo, hi = wilson(k, episodes)
    return {"map": map_, "pursuer": pursuer, "evader": evader, "episodes": episodes, "captures": k,
            "capture_rate": k / episodes, "wilson95": [round(lo, 3), round(hi, 3)],
            "median_capture_time_s": float(np.median(times[captured])) if k else None,
            "outcomes": {o: outcome.count(o) for o in sorted(set(outcome))}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", action="append", default=None)
    ap.add_argument("--pursuer", action="append", required=True)
    ap.add_argument("--evader", action="append", required=True)
    ap.add_argument("--episodes", type=int, default=200)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    for m in args.map or ["maps/paper.yaml", "maps/forest.yaml"]:
        for p in args.pursuer:
            for e in args.evader:
                print(json.dumps(evaluate(m, p, e, args.episodes, args.seed, args.threads)), flush=True)


if __name__ == "__main__":
    main()
