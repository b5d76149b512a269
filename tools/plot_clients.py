#!/usr/bin/env python3
"""The learning curves of the field's clients on a peg3d id (docs/python.md): Stable-Baselines3's Monitor logs
(examples/sb3_ppo.py --out DIR) and the CleanRL-style script's CSV (examples/cleanrl_ppo.py --log FILE), as the
mean episodic return of the last 100 episodes against env steps.

    tools/plot_clients.py --sb3 results/sb3 --cleanrl results/cleanrl.csv --out curves.png
"""

import argparse
import csv
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def sb3_curve(folder):
    """Every game's episodes in the order they ended (Monitor's t column), their steps summed over the games."""
    episodes = []
    for path in glob.glob(os.path.join(folder, "*.monitor.csv")):
        with open(path) as f:
            next(f)  # the Monitor's JSON header
            episodes += [(float(r["t"]), float(r["r"]), int(r["l"])) for r in csv.DictReader(f)]
    episodes.sort()
    steps = np.cumsum([e[2] for e in episodes])
    returns = np.array([e[1] for e in episodes])
    mean = np.array([returns[max(0, i - 99):i + 1].mean() for i in range(len(returns))])
    return steps, mean


def cleanrl_curve(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["mean_return"] != "nan"]
    return np.array([int(r["env_steps"]) for r in rows]), np.array([float(r["mean_return"]) for r in rows])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sb3", help="examples/sb3_ppo.py's --out folder")
    ap.add_argument("--cleanrl", help="examples/cleanrl_ppo.py's --log file")
    ap.add_argument("--title", default="peg3d/Pursuer-v0")
    ap.add_argument("--out", default="clients.png")
    args = ap.parse_args()
    fig, ax = plt.subplots(figsize=(7, 4))
    if args.sb3:
        ax.plot(*sb3_curve(args.sb3), label="Stable-Baselines3 PPO")
    if args.cleanrl:
        ax.plot(*cleanrl_curve(args.cleanrl), label="CleanRL-style PPO (gymnasium.make_vec)")
    ax.set_xlabel("env steps")
    ax.set_ylabel("episodic return, mean of the last 100 episodes")
    ax.set_title(args.title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(args.out)


if __name__ == "__main__":
    main()
