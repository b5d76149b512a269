#!/usr/bin/env python3
"""Stable-Baselines3's PPO on a registered peg3d id, as SB3's documentation uses it: make_vec_env by the id,
its Monitor writing each game's episodes to --out, the action space rescaled to [-1, 1] with Gymnasium's
RescaleAction, as SB3 recommends.

    .venv/bin/python examples/sb3_ppo.py --env-id peg3d/Pursuer-v0 --total-timesteps 1000000 --n-envs 8 \
        --env-kwargs '{"map": "maps/paper.yaml", "opponent": "flee"}' --out results/sb3
"""

import argparse
import json
import time

import gymnasium as gym
import numpy as np
from stable_baselines3 import PPO
from stable_baselines3.common.env_util import make_vec_env

import peg3d  # noqa: F401 - registers the environment ids


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--env-id", default="peg3d/Pursuer-v0")
    ap.add_argument("--env-kwargs", default="{}", help="keyword arguments of the environment, as JSON")
    ap.add_argument("--total-timesteps", type=int, default=1_000_000)
    ap.add_argument("--n-envs", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="results/sb3", help="the Monitor's episode logs and the model")
    args = ap.parse_args()
    venv = make_vec_env(args.env_id, n_envs=args.n_envs, seed=args.seed, env_kwargs=json.loads(args.env_kwargs),
                        monitor_dir=args.out, wrapper_class=gym.wrappers.RescaleAction,
                        wrapper_kwargs={"min_action": np.float32(-1), "max_action": np.float32(1)})
    model = PPO("MlpPolicy", venv, n_steps=256, batch_size=256, seed=args.seed, device="cpu", verbose=0)
    start = time.time()
    model.learn(args.total_timesteps)
    model.save(f"{args.out}/model")
    print(json.dumps({"env_steps": model.num_timesteps, "seconds": round(time.time() - start, 1), "out": args.out}))


if __name__ == "__main__":
    main()
