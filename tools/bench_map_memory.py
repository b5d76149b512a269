#!/usr/bin/env python3
"""Resident memory of a batch of sensing games (docs/performance.md, "Maps that grow with what was seen"): the
process's resident size after N games of two agents, each with a 64-ray lidar (16 x 4 over 360 x 60 degrees, 10 m)
and its own map, have played S steps with random steering; with --no-maps the same games without maps, so that the
difference is the maps'. Prints one JSON object.

    .venv/bin/python tools/bench_map_memory.py [--map M] [--games N] [--steps S] [--threads T] [--no-maps]
"""

import argparse
import json
import resource
import time

import numpy as np

import peg3d


def rss_mb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default="maps/paper.yaml")
    ap.add_argument("--games", type=int, default=256)
    ap.add_argument("--steps", type=int, default=1000, help="steps of every game (an episode of the paper arena is 1000)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--no-maps", action="store_true")
    args = ap.parse_args()
    s = {}
    for role in ("pursuer", "evader"):
        s.update({f"{role}.lidar.azimuth_rays": 16, f"{role}.lidar.elevation_rays": 4,
                  f"{role}.lidar.elevation_fov": 60})
        if not args.no_maps:
            s.update({f"{role}.map.enabled": True, f"{role}.observation.obstacles": "own-map"})
    before = rss_mb()
    env = peg3d.vector_env(map=args.map, num_envs=args.games, threads=args.threads, seed=1, set=s)
    made = rss_mb()
    rng = np.random.default_rng(7)
    bounds = {r: env.single_action_space[r].high for r in ("pursuer", "evader")}
    shapes = {r: (args.games,) + env.single_action_space[r].shape for r in bounds}
    env.reset(seed=1)
    start = time.perf_counter()
    for _ in range(args.steps):
        env.step({r: rng.uniform(-1.0, 1.0, shapes[r]) * bounds[r] for r in bounds})
    seconds = time.perf_counter() - start
    after = rss_mb()
    print(json.dumps({"map": args.map, "games": args.games, "steps_each": args.steps, "maps": not args.no_maps,
                      "rss_mb_before": round(before, 1), "rss_mb_made": round(made, 1), "rss_mb_after": round(after, 1),
                      "peak_rss_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, 1),
                      "env_steps_per_s": round(args.games * args.steps / seconds)}, indent=2))


if __name__ == "__main__":
    main()
