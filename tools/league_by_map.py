#!/usr/bin/env python3
"""Per evaluation map, the league's games of every pursuer against every evader (from peg-league's games.csv):
games, capture rate with its Wilson 95 % interval, median and mean capture time, and the capture time's paired
difference from a reference pursuer (the same start, evaluation seed and evader; mean and 95 % normal interval,
over the starts where both captured), and the capture rate's paired difference from it (over every game both
played; mean of the per-game differences of 0 or 1, with its 95 % normal interval, so that an interval clear of
0 is a significant difference).

    tools/league_by_map.py results/league/games.csv --reference pure-pursuit [--markdown]
"""

import argparse
import csv
import math
import statistics
import sys
from collections import defaultdict

Z = 1.959963984540054  # the normal 97.5 % quantile


def wilson(k, n):
    if n == 0:
        return float("nan"), 0.0, 1.0
    p, z2n = k / n, Z * Z / n
    centre = (p + z2n / 2) / (1 + z2n)
    half = Z / (1 + z2n) * math.sqrt(p * (1 - p) / n + z2n / (4 * n))
    return p, max(0.0, centre - half), min(1.0, centre + half)


def mean_interval(xs, fmt):
    """The mean of paired differences with its 95 % normal interval, or "-" with fewer than two pairs."""
    if len(xs) < 2:
        return "-"
    d, s = statistics.fmean(xs), statistics.stdev(xs) / math.sqrt(len(xs))
    return fmt.format(d, d - Z * s, d + Z * s)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("games", help="games.csv of a peg-league run")
    ap.add_argument("--reference", default="pure-pursuit", help="the pursuer the paired differences are taken from")
    ap.add_argument("--markdown", action="store_true", help="a Markdown table instead of plain columns")
    args = ap.parse_args()
    with open(args.games, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{args.games}: no games")
    games = defaultdict(list)   # (map, pursuer, evader) -> rows
    start = {}                  # (map, scenario, seed, pursuer, evader) -> capture time or None
    for r in rows:
        games[(r["map"], r["pursuer"], r["evader"])].append(r)
        t = float(r["capture_time_s"]) if r["captured"] == "1" else None
        start[(r["map"], r["scenario"], r["eval_seed"], r["pursuer"], r["evader"])] = t
    head = ["map", "pursuer", "evader", "games", "capture rate (Wilson 95 %)", "median t", "mean t",
            f"paired diff. vs {args.reference}", f"paired rate diff. vs {args.reference}"]
    out = []
    for (m, p, e), rs in games.items():
        times = [float(r["capture_time_s"]) for r in rs if r["captured"] == "1"]
        rate, lo, hi = wilson(len(times), len(rs))
        diffs, caught = [], []
        for r in rs:
            key = (m, r["scenario"], r["eval_seed"], args.reference, e)
            if key not in start:
                continue
            mine, ref = start[(m, r["scenario"], r["eval_seed"], p, e)], start[key]
            caught.append((mine is not None) - (ref is not None))
            if mine is not None and ref is not None:
                diffs.append(mine - ref)
        paired = "-" if p == args.reference else mean_interval(diffs, "{:+.1f} s [{:+.1f}, {:+.1f}]")
        paired_rate = "-" if p == args.reference else mean_interval(caught, "{:+.3f} [{:+.3f}, {:+.3f}]")
        out.append([m, p, e, str(len(rs)), f"{rate:.3f} [{lo:.3f}, {hi:.3f}]",
                    f"{statistics.median(times):.1f} s" if times else "-",
                    f"{statistics.fmean(times):.1f} s" if times else "-", paired, paired_rate])
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for row in out:
            print("| " + " | ".join(row) + " |")
    else:
        widths = [max(len(h), *(len(row[i]) for row in out)) for i, h in enumerate(head)]
        for row in [head] + out:
            print("  ".join(c.ljust(w) for c, w in zip(row, widths)))


if __name__ == "__main__":
    main()
