#!/usr/bin/env python3
"""Env steps per second of peg3d.vector_env driven from Python with uniform random steering, the work of
`peg-throughput --actions random` (docs/performance.md). With --gymnasium, of gymnasium.make_vec("peg3d/Pursuer-v0")
instead: the pursuer's random steering from Python, the evader's from the C++ `random` policy. --set KEY=VALUE
(repeatable) overrides a configuration field as the programs' --set does, so that sensing games compare with
`peg-throughput --actions random --set ...` on the same work. Prints one JSON object.

    .venv/bin/python tools/bench_vector_env.py [--map M] [--games N] [--threads T] [--steps S] [--gymnasium]
                                               [--set KEY=VALUE ...]
"""

import argparse
import json
import time

import gymnasium
import numpy as np

import peg3d


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default="maps/paper.yaml")
    ap.add_argument("--games", type=int, default=256)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--steps", type=int, default=2_000_000, help="env steps over all games")
    ap.add_argument("--gymnasium", action="store_true", help="the registered Gymnasium vector env")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a configuration override")
    args = ap.parse_args()
    settings = {}
    for item in args.set:
        key, sep, value = item.partition("=")
        if not sep:
            ap.error(f"--set {item}: KEY=VALUE")
        settings[key] = value
    rng = np.random.default_rng(7)
    if args.gymnasium:
        env = gymnasium.make_vec("peg3d/Pursuer-v0", num_envs=args.games, vectorization_mode="vector_entry_point",
                                 map=args.map, threads=args.threads, opponent="random", seed=1, set=settings)
        bound = env.single_action_space.high
        draw = lambda: rng.uniform(-1.0, 1.0, (args.games, 2)) * bound  # noqa: E731
    else:
        env = peg3d.vector_env(map=args.map, num_envs=args.games, threads=args.threads, seed=1, set=settings)
        bounds = {r: env.single_action_space[r].high for r in ("pursuer", "evader")}
        shapes = {r: (args.games,) + env.single_action_space[r].shape for r in bounds}
        draw = lambda: {r: rng.uniform(-1.0, 1.0, shapes[r]) * bounds[r] for r in bounds}  # noqa: E731
    env.reset(seed=1)
    steps = 0
    start = time.perf_counter()
    while steps < args.steps:
        env.step(draw())
        steps += args.games
    seconds = time.perf_counter() - start
    print(json.dumps({"map": args.map, "games": args.games, "threads": args.threads, "gymnasium": args.gymnasium,
                      "set": settings, "steps": steps, "seconds": seconds, "env_steps_per_s": steps / seconds}, indent=2))


if __name__ == "__main__":
    main()
