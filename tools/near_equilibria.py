#!/usr/bin/python3
"""What a peg3d.selfplay run's last meta-game allows near its equilibrium (docs/learning.md, "Self-play").

Usage: tools/near_equilibria.py RUN_DIR [--role evader|pursuer] [--against MEMBER] [--eps E ...] [--json]

The final mixtures solve the zero-sum matrix of RUN_DIR/summary.json exactly, but its entries are estimates from
`eval_games` games each: near a value of 1 a single game moves an entry by 1/games. This prints, for each margin
E (payoff units), the mixtures of ROLE that are within E of the game's value against every member of the other
role (evaders: M y <= value + E; pursuers: x M >= value - E), and among them, as capture rates:
- the one the member AGAINST of the other role does best against (evaders: the least caught by it; pursuers:
  catching it most), and
- the one that does best on average against the whole other population (each member weighted alike).
Both are linear programs (scipy.optimize.linprog). E = 0 gives the equilibrium's own choice of value.

Exit status: 0 when printed, 2 (with "error: ..." on stderr) when summary.json is missing or malformed or a
name is not a member. Runs under Debian's /usr/bin/python3 with python3-numpy and python3-scipy.
"""

import argparse
import json
import os
import sys

import numpy as np
from scipy.optimize import linprog


class Error(Exception):
    pass


def load(run):
    path = os.path.join(run, "summary.json")
    try:
        with open(path) as f:
            doc = json.load(f)
        members = doc["members"]
        payoff, rate = np.array(doc["payoff"], dtype=float), np.array(doc["capture_rate"], dtype=float)
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise Error(f"{path}: not a self-play summary ({e})") from None
    shape = (len(members["pursuer"]), len(members["evader"]))
    if payoff.shape != shape or rate.shape != shape or not np.all(np.isfinite(payoff)):
        raise Error(f"{path}: payoff and capture_rate must be finite {shape[0]} x {shape[1]} matrices")
    return members, payoff, rate


def _lp(objective, a_ub, b_ub):
    """min objective . y over the simplex with a_ub y <= b_ub."""
    n = len(objective)
    r = linprog(objective, A_ub=a_ub, b_ub=b_ub, A_eq=np.ones((1, n)), b_eq=[1.0], bounds=[(0, None)] * n)
    if r.status != 0:
        raise Error(f"linear program failed: {r.message}")
    y = np.clip(r.x, 0.0, None)  # the solver's -1e-12s
    return y / y.sum()


def near_equilibria(members, payoff, rate, role, against, margins):
    """One entry per margin: the mixtures of `role` described in the module's docstring."""
    other = "pursuer" if role == "evader" else "evader"
    if against not in members[other]:
        raise Error(f"--against: '{against}' is not a member of the {other}s ({', '.join(members[other])})")
    # As the evaders' problem (minimise): the pursuers' is the same with the payoff negated and transposed.
    sign = 1.0 if role == "evader" else -1.0
    m, c = (payoff, rate) if role == "evader" else (payoff.T, rate.T)
    m, c = sign * m, sign * c
    rows, cols = m.shape
    # The value: min over mixtures y of max_i (m y)_i, with t = that max as an extra variable.
    r = linprog(np.r_[np.zeros(cols), 1.0], A_ub=np.c_[m, -np.ones(rows)], b_ub=np.zeros(rows),
                A_eq=np.r_[np.ones(cols), 0.0][None], b_eq=[1.0], bounds=[(0, None)] * cols + [(None, None)])
    if r.status != 0:
        raise Error(f"linear program failed: {r.message}")
    value = float(r.x[-1])
    a = members[other].index(against)
    out = []
    for eps in margins:
        entry = {"margin": eps}
        # A margin below the solver's rounding would leave no mixture; 1e-9 payoff units keep the equilibrium's.
        bound = np.full(rows, value + eps + 1e-9)
        for name, objective in (("against", c[a]), ("population", c.mean(axis=0))):
            y = _lp(objective, m, bound)
            entry[name] = {"mixture": {members[role][j]: round(float(w), 4) for j, w in enumerate(y) if w > 1e-4},
                           "capture_rate_by_" + against: float(sign * c[a] @ y),
                           "capture_rate_mean": float(sign * c.mean(axis=0) @ y),
                           "worst_payoff": float(sign * (m @ y).max())}
        out.append(entry)
    return {"role": role, "against": against, "value": sign * value, "entries": out}


def main(argv=None):
    p = argparse.ArgumentParser(prog="near_equilibria.py", description=__doc__.split("\n\n")[0])
    p.add_argument("run")
    p.add_argument("--role", choices=("evader", "pursuer"), default="evader")
    p.add_argument("--against", default=None, help="a member of the other role (default: pn for evaders, "
                   "flee for pursuers)")
    p.add_argument("--eps", type=float, nargs="+", default=[0.0, 0.01, 0.02, 0.03])
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    against = args.against or ("pn" if args.role == "evader" else "flee")
    try:
        if any(not (0.0 <= e <= 1.0) for e in args.eps):
            raise Error("--eps: margins in [0, 1] payoff units")
        result = near_equilibria(*load(args.run), args.role, against, args.eps)
    except Error as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    print(f"{args.run}: the {args.role}s' mixtures within a margin of the value {result['value']:.4f}"
          f" (capture rates: by {against}{' of' if args.role == 'pursuer' else ''} and on average)")
    for e in result["entries"]:
        for name, label in (("against", against), ("population", "average")):
            d = e[name]
            print(f"  margin {e['margin']:.3f}, best against {label}: {against} {d['capture_rate_by_' + against]:.3f}, "
                  f"average {d['capture_rate_mean']:.3f}, worst payoff {d['worst_payoff']:.4f}; "
                  + ", ".join(f"{k} {w:.2f}" for k, w in d["mixture"].items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
