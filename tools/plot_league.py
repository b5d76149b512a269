#!/usr/bin/python3
"""Draws the cross-play heat-maps and the learning curves of a peg-league result folder (formats: docs/results.md).

Usage: tools/plot_league.py RESULTS_DIR

Reads RESULTS_DIR/matrix.csv (one row per pursuer group and evader group) and writes RESULTS_DIR/league.png
(saved to a temporary name, then renamed): two heat-maps side by side, pursuers down, evaders across,
  left   capture rate, each cell with the rate and its 95% Wilson interval
  right  mean evader survival time (s, censored at the time limit), each cell with its 95% t interval
Reads RESULTS_DIR/learning_curves.csv, when there is one, and writes RESULTS_DIR/league_learning.png: per
algorithm, the capture rate and the episode time of its co-learning training episodes (opponent-pool episodes
left out), a trailing mean of LEARNING_WINDOW episodes, mean +- 1 standard error over the training seeds.

Exit status: 0 when the figure was written, 2 (with "error: ..." on stderr) when RESULTS_DIR or matrix.csv is
missing or malformed. Runs under Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""

import csv
import math
import os
import sys
import tempfile

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_paper import algorithm_color, curve_arrays, draw_curves  # noqa: E402

DPI = 130
LEARNING_WINDOW = 50
COLUMNS = ("pursuer", "evader", "games", "capture_rate", "capture_rate_lo", "capture_rate_hi", "evader_survival_s",
           "evader_survival_lo", "evader_survival_hi")


class InputError(Exception):
    """A missing or malformed input file; the message names the file."""


def number(text):
    return float("nan") if text in ("", "nan") else float(text)


def read_rows(path, columns):
    """The rows of a CSV file as dicts; InputError when it cannot be read, or has rows without `columns`."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from e
    missing = [c for c in columns if rows and c not in rows[0]]
    if missing:
        raise InputError(f"{path}: missing columns {', '.join(missing)}")
    return rows


def read_matrix(path):
    rows = read_rows(path, COLUMNS)
    if not rows:
        raise InputError(f"{path}: no rows")
    pursuers, evaders, cells = [], [], {}
    for i, r in enumerate(rows, start=2):
        try:
            values = {c: number(r[c]) for c in COLUMNS[2:]}
        except ValueError as e:
            raise InputError(f"{path}:{i}: {e}") from e
        if r["pursuer"] not in pursuers:
            pursuers.append(r["pursuer"])
        if r["evader"] not in evaders:
            evaders.append(r["evader"])
        cells[(r["pursuer"], r["evader"])] = values
    return pursuers, evaders, cells


def heat_map(ax, pursuers, evaders, cells, key, lo, hi, fmt, cmap, vmin, vmax, title):
    grid = np.full((len(pursuers), len(evaders)), np.nan)
    for i, p in enumerate(pursuers):
        for j, e in enumerate(evaders):
            if (p, e) in cells:
                grid[i, j] = cells[(p, e)][key]
    image = ax.imshow(grid, cmap=cmap, vmin=vmin, vmax=vmax, aspect="auto")
    for i, p in enumerate(pursuers):
        for j, e in enumerate(evaders):
            c = cells.get((p, e))
            if c is None or math.isnan(c[key]):
                continue
            r, g, b, _ = image.cmap(image.norm(c[key]))  # dark text on light cells, light on dark
            ax.text(j, i, f"{fmt(c[key])}\n[{fmt(c[lo])}, {fmt(c[hi])}]\nn={int(c['games'])}", ha="center",
                    va="center", fontsize=7, color="black" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "white")
    ax.set_xticks(range(len(evaders)), evaders, rotation=30, ha="right")
    ax.set_yticks(range(len(pursuers)), pursuers)
    ax.set_xlabel("evader")
    ax.set_ylabel("pursuer")
    ax.set_title(title)
    plt.colorbar(image, ax=ax, fraction=0.046, pad=0.04)


def read_learning_curves(path):
    """Per algorithm: (capture flags, episode times), training seeds x episodes, nan for opponent-pool episodes."""
    rows = read_rows(path, ("algorithm", "train_seed", "episode", "pool_opponent", "captured", "episode_time_s"))
    items = {}
    for i, r in enumerate(rows, start=2):
        try:
            seed, episode = int(r["train_seed"]), int(r["episode"])
            captured, seconds = number(r["captured"]), number(r["episode_time_s"])
        except ValueError as e:
            raise InputError(f"{path}:{i}: {e}") from e
        if seed < 0 or episode < 0:
            raise InputError(f"{path}:{i}: negative train_seed or episode")
        if r["pool_opponent"] != "":
            captured = seconds = float("nan")
        items.setdefault(r["algorithm"], []).append((seed, episode, captured, seconds))
    return curve_arrays(items)


def plot_learning(curves, path):
    fig, (ax_rate, ax_time) = plt.subplots(2, 1, figsize=(8.0, 6.5), sharex=True)
    for algorithm, curve in curves.items():
        draw_curves((ax_rate, ax_time), curve, LEARNING_WINDOW, algorithm_color(algorithm), algorithm)
    ax_rate.set_ylim(-0.03, 1.03)
    ax_rate.set_ylabel("capture rate")
    ax_time.set_ylabel("episode time (s)")
    ax_time.set_xlabel("training episode")
    for ax in (ax_rate, ax_time):
        ax.grid(color="#e3e3e3")
    ax_rate.legend(fontsize=9, frameon=False)
    ax_rate.set_title(f"Co-learning training episodes (opponent-pool episodes left out)\ntrailing mean of "
                      f"{LEARNING_WINDOW} episodes, mean ± 1 standard error over the training seeds", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path)
    plt.close(fig)


def save_figure(fig, path):
    folder, name = os.path.split(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=DPI, format="png", metadata={"Software": None})
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def main(argv):
    if len(argv) != 2:
        print("usage: plot_league.py RESULTS_DIR", file=sys.stderr)
        return 2
    folder = argv[1]
    curves_file = os.path.join(folder, "learning_curves.csv")
    try:
        if not os.path.isdir(folder):
            raise InputError(f"{folder}: not a folder")
        pursuers, evaders, cells = read_matrix(os.path.join(folder, "matrix.csv"))
        curves = read_learning_curves(curves_file) if os.path.exists(curves_file) else {}
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    survival = [c["evader_survival_s"] for c in cells.values() if not math.isnan(c["evader_survival_s"])]
    top = max(survival) if survival else 1.0
    width = 2.0 + 1.3 * len(evaders)
    fig, axes = plt.subplots(1, 2, figsize=(2 * width, 1.0 + 0.7 * len(pursuers)))
    heat_map(axes[0], pursuers, evaders, cells, "capture_rate", "capture_rate_lo", "capture_rate_hi",
             lambda v: f"{v:.2f}", "viridis", 0.0, 1.0, "capture rate [95% CI]")
    heat_map(axes[1], pursuers, evaders, cells, "evader_survival_s", "evader_survival_lo", "evader_survival_hi",
             lambda v: f"{v:.0f}", "magma", 0.0, top, "evader survival, s [95% CI]")
    fig.tight_layout()
    save_figure(fig, os.path.join(folder, "league.png"))
    plt.close(fig)
    if curves:
        plot_learning(curves, os.path.join(folder, "league_learning.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
