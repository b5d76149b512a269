#!/usr/bin/env python3
"""Env steps per second of peg3d.vector_env driven from Python with uniform random steering, the work of
`peg-throughput --actions random` (docs/performance.md). Prints one JSON object.

    .venv/bin/python tools/bench_vector_env.py [--map M] [--games N] [--threads T] [--steps S]
"""

import argparse
import json
import time

import numpy as np

import peg3d


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default="maps/paper.yaml")
    ap.add_argument("--games", type=int, default=256)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--steps", type=int, default=2_000_000, help="env steps over all games")
    args = ap.parse_args()
    env = peg3d.vector_env(map=args.map, num_envs=args.games, threads=args.threads, seed=1)
    env.reset(seed=1)
    rng = np.random.default_rng(7)
    bounds = {r: env.single_action_space[r].high for r in ("pursuer", "evader")}
    shapes = {r: (args.games,) + env.single_action_space[r].shape for r in bounds}
    steps = 0
    start = time.perf_counter()
    while steps < args.steps:
        actions = {r: rng.uniform(-1.0, 1.0, shapes[r]) * bounds[r] for r in bounds}
        env.step(actions)
        steps += args.games
    seconds = time.perf_counter() - start
    print(json.dumps({"map": args.map, "games": args.games, "threads": args.threads, "steps": steps,
                      "seconds": seconds, "env_steps_per_s": steps / seconds}, indent=2))


if __name__ == "__main__":
    main()
