#!/usr/bin/python3
"""Draws a peg3d.selfplay run's exploitability curve and its last payoff matrix (docs/learning.md, "Self-play").

Usage: tools/plot_selfplay.py RUN_DIR [OUT.png]

Reads RUN_DIR/summary.json and writes OUT.png (default RUN_DIR/selfplay.png; saved to a temporary name, then
renamed): left, per iteration, the exploitability of that iteration's mixtures against every member the run made
(the pursuers' best payoff against the evaders' mixture less the evaders' best), with both terms; right, the
capture rates of the last matrix, pursuers down, evaders across, the final mixtures' weights in the labels.

Exit status: 0 when the figure was written, 2 (with "error: ..." on stderr) when summary.json is missing or
malformed. Runs under Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib.
"""

import json
import os
import sys
import tempfile

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def label(member):
    """'BR k' for a run's own best responses; a first member from another run's folder gets that run's name."""
    parts = os.path.splitext(member)[0].split("/")
    run = parts[-3].removeprefix("selfplay_") + " " if len(parts) > 2 else ""
    name = "/".join(parts[-2:])
    return run + name.replace("iteration_", "BR ").replace("/pursuer", "").replace("/evader", "")


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    run = argv[1]
    out = argv[2] if len(argv) == 3 else os.path.join(run, "selfplay.png")
    try:
        with open(os.path.join(run, "summary.json")) as f:
            s = json.load(f)
        curve = s["curve"]
        rates = np.array(s["capture_rate"], dtype=float)
        members, x, y = s["members"], s["pursuer_mixture"], s["evader_mixture"]
        if rates.shape != (len(members["pursuer"]), len(members["evader"])):
            raise ValueError("capture_rate: not members x members")
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"error: {run}: {e}", file=sys.stderr)
        return 2
    fig, (a, b) = plt.subplots(1, 2, figsize=(13, 5))
    it = [c["iteration"] for c in curve]
    a.plot(it, [c["exploitability"] for c in curve], "o-", label="exploitability")
    a.plot(it, [c["pursuer_best_response"] for c in curve], "^--", label="pursuers' best payoff vs the evaders' mixture")
    a.plot(it, [c["evader_best_response"] for c in curve], "v--", label="evaders' best payoff vs the pursuers' mixture")
    a.set_xlabel("iteration (mixtures solved before its best responses; last: final)")
    a.set_ylabel("payoff (capture rate + tie-break)")
    a.set_ylim(-0.05, 1.1)
    a.grid(alpha=0.3)
    a.legend(fontsize=8)
    a.set_title("exploitability against every member of the run")
    b.imshow(rates, vmin=0, vmax=1, cmap="viridis")
    for i in range(rates.shape[0]):
        for j in range(rates.shape[1]):
            b.text(j, i, f"{rates[i, j]:.2f}", ha="center", va="center", color="w" if rates[i, j] < 0.6 else "k", fontsize=8)
    b.set_yticks(range(rates.shape[0]), [f"{label(m)} ({w:.2f})" for m, w in zip(members["pursuer"], x)])
    # Slanted: with FACL members the evaders' labels are too wide to stand side by side.
    b.set_xticks(range(rates.shape[1]), [f"{label(m)} ({w:.2f})" for m, w in zip(members["evader"], y)], fontsize=8,
                 rotation=45, ha="right", rotation_mode="anchor")
    b.set_title("capture rate (final mixture weights)")
    fig.tight_layout()
    fd, tmp = tempfile.mkstemp(suffix=".png", dir=os.path.dirname(os.path.abspath(out)))
    os.close(fd)
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
