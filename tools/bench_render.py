#!/usr/bin/env python3
"""Frames per second of render_mode="rgb_array" (640 x 480, src/view/frame_renderer.hpp) on one core: render()
alone, and a game step with its render, as a video recorder does. Prints one JSON object.

    .venv/bin/python tools/bench_render.py [--map maps/forest.yaml] [--frames 2000]
"""

import argparse
import json
import time

import numpy as np

import peg3d


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default="maps/forest.yaml")
    ap.add_argument("--frames", type=int, default=2000)
    args = ap.parse_args()
    env = peg3d.parallel_env(map=args.map, render_mode="rgb_array")
    env.reset(seed=1)
    rng = np.random.default_rng(3)
    start = time.perf_counter()
    for _ in range(args.frames):
        env.render()
    alone = time.perf_counter() - start
    start, frames = time.perf_counter(), 0
    while frames < args.frames:
        if not env.agents:
            env.reset()
        env.step({a: rng.uniform(-1, 1, 2) * env.action_space(a).high for a in env.agents})
        env.render()
        frames += 1
    stepped = time.perf_counter() - start
    print(json.dumps({"map": args.map, "frames": args.frames, "render_fps": args.frames / alone,
                      "step_and_render_fps": args.frames / stepped}, indent=2))


if __name__ == "__main__":
    main()
