"""peg3d.selfplay: pursuer teams and evaders grown together by self-play over populations (PSRO; docs/learning.md,
"Self-play"), judged by their exploitability.

    python -m peg3d.selfplay --map maps/open_wall.yaml --iterations 6 --steps 300000 --out results/selfplay_wall

Each role's population starts from classic players (and any policy files given). Every iteration:
1. plays each new pairing of a pursuer member against an evader member on held-out seeds, on the C++ side
   (`eval_games` games, the same seeds for every pairing): the payoff is the capture rate, with the capture time
   as a tie-breaker (`payoff`);
2. solves the zero-sum meta-game of that matrix by fictitious play (`solve_zero_sum`): a mixture per role;
3. trains one best response per role against the other role's mixture (peg3d.mappo: a shared actor for the
   role's team, which sees its teammates and nearest opponents, and a centralised critic), the opponents drawn
   per episode from the mixture inside the C++ batch; both join their populations. With `facl_episodes`, the
   paper's learner trains one more best response per role, in C++ (`_core.train_facl`): FACL tables whose inputs
   include the sight entries (`facl_set`), against the same mixture; they join the populations too. With
   `league_share`, both train against a league instead: that share of their opponents drawn from the other role's
   whole population by prioritised fictitious self-play (`league_weights`), the rest from the mixture.
An iteration's files are written before its record (`iteration_K/state.json`), so an interrupted run resumes
from its last finished iteration (`resume=True`) with the same results as one never stopped; resumed with more
`iterations`, a run (finished or not) is extended to the run that asked for them from the start. After the last
iteration a fresh best response per role, trained against the final mixtures, measures their exploitability.

Everything is seeded from `seed`; with Ray (`ray_address`) the evaluations and trainings run as Ray tasks and give
the same files.
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import os
import socket
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from . import _core
from ._roles import ROLES, other_role
from .mappo import Budget
from .vector import VectorEnv

# The files of a run's ending (`SelfPlay._finish`), in its folder; an extended run removes them before any new work.
SUMMARY, EXPLOITABILITY = "summary.json", "exploitability.json"
FINAL, BEST_RESPONSE = "final_{}.json", "best_response_{}.json"  # .format(role)
ENDING = (SUMMARY, EXPLOITABILITY) + tuple(f.format(r) for f in (FINAL, BEST_RESPONSE) for r in ROLES)
TIE_BREAK = 0.01  # payoff = capture rate + TIE_BREAK x (1 - capture time / time limit), averaged over games


@dataclass
class Settings:
    """A self-play run. Units: steps are env steps (games x game steps)."""
    map: str = "maps/open_wall.yaml"
    scenario: list | None = None      # the map's starts to play (None: those with its first start's teams)
    # Configuration overrides, key -> value (as parallel_env's set). Random headings by default: with the fixed
    # headings of a map's starts, deterministic players play each start the same way in every game.
    set: dict = field(default_factory=lambda: {"initial_heading": "random"})
    neighbours: int = 3               # slots of nearest opponents and teammates each learner sees, in [0, 16]
    pursuers: list = field(default_factory=lambda: list(_core.BASELINE_PLAYERS["pursuer"]))  # the first members
    evaders: list = field(default_factory=lambda: list(_core.BASELINE_PLAYERS["evader"]))
    iterations: int = 4               # best responses per role, >= 1
    budget: Budget = Budget()         # each best response's training
    # Env steps of one role's best responses, role -> steps >= 1, in place of budget.steps for that role (a role
    # left out trains budget.steps); the exploitability's fresh ones too, unless final_budget is given.
    role_steps: dict = field(default_factory=dict)
    final_budget: Budget | None = None  # the exploitability's fresh best responses, both roles (None: budget_of)
    # FACL best responses: training episodes per role and iteration, in [0, 10^7] (0: none, MAPPO's alone), and
    # the FACL learners' own settings, key -> value under their role (pursuer.KEY or evader.KEY): by default the
    # sight entries are two more fuzzy inputs (in sight now: sets at 0 and 1; the sighting's age: observation.sets
    # sets over [0, 10 s]).
    facl_episodes: int = 0
    facl_set: dict = field(default_factory=lambda: {"observation.sight_inputs": "true"})
    # Share of each best response's opponents drawn from the other role's whole population, in [0, 1) (0: the
    # meta-game's mixture alone, PSRO's rule): weighted by prioritised fictitious self-play (`league_weights`), the
    # rest from the mixture. The exploitability's fresh best responses train against the final mixture alone.
    league_share: float = 0.0
    eval_games: int = 64              # held-out games per pairing, in [1, 65536]
    eval_threads: int = 1             # C++ threads playing them, >= 1
    solver_iterations: int = 20000    # fictitious play's rounds, >= 1
    seed: int = 1                     # root seed, in [0, 2^63)

    def check(self):
        if not isinstance(self.map, (str, os.PathLike)):
            raise TypeError("map: a map file")
        for name, low, high in (("neighbours", 0, 16), ("iterations", 1, 10_000), ("eval_games", 1, 65536),
                                ("eval_threads", 1, 256), ("solver_iterations", 1, 10**7), ("seed", 0, 2**63 - 1),
                                ("facl_episodes", 0, 10**7)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not low <= v <= high:
                raise ValueError(f"{name}: an integer in [{low}, {high}], not {v!r}")
        for role in ROLES:
            members = getattr(self, role + "s")
            if not isinstance(members, (list, tuple)) or not members:
                raise ValueError(f"{role}s: at least one player or policy file")
            for k, m in enumerate(members):
                if not isinstance(m, (str, os.PathLike)) or not str(m):
                    raise TypeError(f"{role}s.{k}: a player's name or a policy file, not {m!r}")
        v = self.league_share
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not 0 <= v < 1:
            raise ValueError(f"league_share: a number in [0, 1), not {v!r}")
        if not isinstance(self.facl_set, dict) or not all(isinstance(k, str) and k for k in self.facl_set):
            raise TypeError("facl_set: a dict of setting -> value")
        if not isinstance(self.role_steps, dict):
            raise TypeError("role_steps: a dict of role -> env steps")
        for role in self.role_steps:
            if role not in ROLES:
                raise ValueError(f"role_steps: {role!r} is not a role ({', '.join(ROLES)})")
        self.budget.check()
        for role in self.role_steps:  # the role's budget: its steps are the only field not checked above
            self.budget_of(role).check(f"role_steps.{role}")
        if self.final_budget is not None:
            self.final_budget.check("final_budget")

    def budget_of(self, role, final=False):
        """The budget of `role`'s best responses (`final`: the exploitability's fresh one)."""
        if final and self.final_budget is not None:
            return self.final_budget
        steps = self.role_steps.get(role)
        return self.budget if steps is None else dataclasses.replace(self.budget, steps=steps)

    def to_json(self):
        d = dataclasses.asdict(self)
        d["map"] = str(self.map)
        d["pursuers"], d["evaders"] = [str(m) for m in self.pursuers], [str(m) for m in self.evaders]
        return d


def derive_seed(root, *path):
    """A 63-bit seed below `root` for `path` (names and numbers): independent streams for every job."""
    h = hashlib.blake2b(json.dumps([int(root)] + [str(p) for p in path]).encode(), digest_size=8)
    return int.from_bytes(h.digest(), "little") >> 1


def solve_zero_sum(matrix, iterations=20000):
    """The meta-game's mixtures by fictitious play (Brown 1951; Robinson 1951 proved it converges in zero-sum
    games): each round the row player (pursuers, maximising) and the column player (evaders, minimising) play a
    best response to the other's empirical mixture so far, ties to the lowest index. Returns (x, y, low, high):
    the empirical mixtures and bounds on the game's value, min(x M) <= value <= max(M y); high - low is the
    mixtures' exploitability within the matrix (0 at an exact equilibrium)."""
    m = np.asarray(matrix, dtype=np.float64)
    if m.ndim != 2 or 0 in m.shape or not np.all(np.isfinite(m)):
        raise ValueError("matrix: a finite 2-D payoff matrix")
    rows, cols = np.zeros(m.shape[0]), np.zeros(m.shape[1])
    row_sum, col_sum = np.zeros(m.shape[0]), np.zeros(m.shape[1])
    i, j = 0, 0
    for _ in range(int(iterations)):
        rows[i] += 1
        cols[j] += 1
        row_sum += m[:, j]
        col_sum += m[i, :]
        i, j = int(np.argmax(row_sum)), int(np.argmin(col_sum))
    x, y = rows / rows.sum(), cols / cols.sum()
    return x, y, float((x @ m).min()), float((m @ y).max())


def league_weights(rate, x, y, share):
    """Each role's training opponents, role -> weights over the other role's members: (1 - share) x the meta-game's
    mixture + share x prioritised fictitious self-play over the whole population (AlphaStar, Vinyals et al. 2019:
    opponent o in proportion to (1 - P[the learner beats o])^2, P estimated by the learner's role's mixture; uniform
    when no member beats it). `rate`: capture rates, pursuers x evaders; x, y: the pursuers' and evaders' mixtures."""
    rate, x, y = np.asarray(rate, dtype=np.float64), np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    if share == 0:
        return {"pursuer": y, "evader": x}
    # How often each evader escapes the pursuers' mixture; how often each pursuer catches the evaders' mixture.
    hard = {"pursuer": 1.0 - x @ rate, "evader": rate @ y}
    out = {}
    for role, mixture in (("pursuer", y), ("evader", x)):
        w = np.clip(hard[role], 0.0, 1.0) ** 2
        w = w / w.sum() if w.sum() > 0 else np.full(len(w), 1.0 / len(w))
        out[role] = (1.0 - share) * mixture + share * w
    return out


def payoff(caught, steps, max_steps):
    """The pursuers' payoff over games: the share of evaders caught, and TIE_BREAK x how early (1 - game steps /
    max steps) for the caught. `caught`: games x evaders, the share caught per game; `steps`: the games' steps."""
    share = np.asarray(caught, dtype=np.float64).mean(axis=1)
    early = 1.0 - np.minimum(np.asarray(steps, dtype=np.float64), max_steps) / max_steps
    return float(np.mean(share * (1.0 + TIE_BREAK * early)))


def _env_keywords(settings):
    return dict(map=settings.map, scenario=settings.scenario, set=settings.set, neighbours=settings.neighbours)


def play_pairing(settings, pursuer, evader, games, seed):
    """`games` games of `pursuer` against `evader` (players, files or mixtures), both on the C++ side, from
    `seed`: each game's first episode. Returns {"payoff", "capture_rate", "mean_steps", "games"}."""
    env = VectorEnv(num_envs=games, threads=min(settings.eval_threads, games), seed=seed,
                    opponents={"pursuer": pursuer, "evader": evader}, **_env_keywords(settings))
    env.reset(seed=seed)
    evaders = env.agent_counts["evader"]
    caught = np.zeros((games, evaders), dtype=bool)
    steps = np.zeros(games, dtype=np.int64)
    ended = np.zeros(games, dtype=bool)
    max_steps = env._batch.max_steps
    k, limit = 0, max_steps + 2
    while not ended.all() and k < limit:
        _, _, _, _, info = env.step({})
        k += 1
        fresh = info["reset"].astype(bool)  # this step reset the game: its episode ended in the step before
        newly = fresh & ~ended
        steps[newly] = k - 1
        ended |= fresh
        live = ~ended
        caught[live] |= info["captured"]["evader"][live].astype(bool)
    env.close()
    assert ended.all(), "an episode outlasted the time limit"
    share = caught.mean(axis=1)
    return {"payoff": payoff(caught, steps, max_steps), "capture_rate": float(share.mean()),
            "mean_steps": float(steps.mean()), "games": int(games)}


def _train(settings, role, opponents, budget, seed):
    """A best response of `role` against the other role's mixture `opponents` ({member: weight}): a Network."""
    from . import mappo
    other = other_role(role)
    env = dict(_env_keywords(settings), opponents={other: opponents})
    return mappo.train(role, env, budget, seed)


def _facl_sets(settings, role):
    """The configuration overrides of a FACL best response of `role`: the run's, then its learners' own."""
    sets = dict(settings.set, **{f"{role}.policy": "facl"})
    sets.update({f"{role}.{k}": v for k, v in settings.facl_set.items()})
    return sets


def _train_facl(settings, role, opponent, episodes, seed):
    """A FACL best response of `role`, trained in C++ against `opponent` (a policy or mixture file of the other
    role): its policy document's text."""
    import tempfile
    from . import _loading
    with tempfile.TemporaryDirectory(prefix="peg3d-facl-") as tmp:
        out = os.path.join(tmp, "policy.json")
        _core.train_facl(_loading.resolve(settings.map), _loading.config_source("peg3d"),
                         _loading.overrides(_facl_sets(settings, role)), list(settings.scenario or []), role,
                         str(opponent), int(episodes), int(seed), out)
        with open(out) as f:
            return f.read()


class _Runner:
    """Runs jobs in this process, or as Ray tasks on a cluster."""

    def __init__(self, ray_address=None):
        self.ray = None
        if ray_address is not None:
            try:
                import ray
            except ImportError as e:
                raise ImportError("ray_address: Ray is not installed (pip install \"peg3d[ray]\")") from e
            host, sep, port = str(ray_address).removeprefix("ray://").rpartition(":")
            if sep and port.isdigit():
                # Ray's own connect retries for a minute or more; a closed port is refused at once.
                try:
                    socket.create_connection((host, int(port)), timeout=10).close()
                except OSError as e:
                    raise ConnectionError(f"ray_address: no Ray cluster at {ray_address!r}: {e}") from None
            try:
                ray.init(address=ray_address, ignore_reinit_error=True, log_to_driver=False)
            except Exception as e:  # noqa: BLE001 - Ray raises several kinds for an unreachable cluster
                raise ConnectionError(f"ray_address: no Ray cluster at {ray_address!r}: {e}") from e
            self.ray = ray
            self._remote = {kind: ray.remote(f) for kind, f in self.JOBS.items()}

    JOBS = {"play": play_pairing, "train": _train, "train_facl": _train_facl}

    def map(self, kind, calls):
        """Results of `kind` ("play", "train" or "train_facl") for each argument tuple, in order."""
        if self.ray is None:
            return [self.JOBS[kind](*c) for c in calls]
        return self.ray.get([self._remote[kind].remote(*c) for c in calls])


def _absolute(member, out):
    """A member as the batch takes it: a player's name, or a file (relative paths are the run folder's)."""
    m = str(member)
    if m.endswith(".json") and not os.path.isabs(m) and os.path.exists(os.path.join(out, m)):
        return os.path.abspath(os.path.join(out, m))
    return m


def _write_json(path, doc):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def _mixture(members, weights, out):
    return {_absolute(m, out): float(w) for m, w in zip(members, weights) if w > 0}


def _write_mixture(path, role, members, weights, out):
    """A peg3d-mixture file (the C++ side draws one member per episode) of the members of weight > 0: the run's
    files (named relative to `out`) named relative to the mixture file's folder, which the C++ loader reads them
    from; other files (the first members given, relative to the working folder) by their absolute paths; players
    by name."""
    folder = os.path.dirname(os.path.abspath(path))
    named = []
    for m, w in zip(members, weights):
        if w > 0:
            file = _absolute(m, out)
            if file != str(m):
                policy = os.path.relpath(file, folder)
            elif str(m).endswith(".json") or os.path.exists(str(m)):
                policy = os.path.abspath(str(m))
            else:
                policy = str(m)
            named.append({"policy": policy, "weight": float(w)})
    _write_json(path, {"format": "peg3d-mixture", "version": 1, "role": role, "trained_by": "peg3d.selfplay",
                       "members": named})


class SelfPlay:
    """A self-play run in folder `out` (see the module's help). `run()` plays it to the end and returns the
    summary it writes to out/summary.json."""

    def __init__(self, settings, out, resume=False, ray_address=None, log=print):
        settings.check()
        self.settings, self.out, self.log = settings, str(out), log
        path = os.path.join(self.out, "settings.json")
        extend = False
        if os.path.exists(path):
            with open(path) as f:
                saved = json.load(f)
            if not resume:
                raise FileExistsError(f"{self.out}: a self-play run is there already (resume=True / --resume continues it)")
            # A run made before a setting existed was made with its default.
            now, defaults = json.loads(json.dumps(settings.to_json())), json.loads(json.dumps(Settings().to_json()))
            saved = {k: saved.get(k, defaults[k]) for k in now}
            # More iterations extend the run: iteration k's seeds do not depend on the count, so an extended run is
            # the run that asked for them from the start. Fewer would drop finished work: refused.
            extend = saved["iterations"] < now["iterations"]
            if now["iterations"] < saved["iterations"]:
                raise ValueError(f"{path}: the run there has {saved['iterations']} iterations; --iterations "
                                 f"{now['iterations']} would drop some (more extend it)")
            saved["iterations"] = now["iterations"]
            if saved != now:
                changed = sorted(k for k in saved if saved[k] != now.get(k))
                raise ValueError(f"{path}: the run there was made with other settings ({', '.join(changed)})")
        self._check_members()
        self.runner = _Runner(ray_address)  # an unreachable cluster, before anything is written
        os.makedirs(self.out, exist_ok=True)
        if extend:
            # The shorter run's ending was measured against its own final mixtures: gone before any new work, so
            # that no file of the old ending outlives an interruption of the new iterations.
            for name in ENDING:
                stale = os.path.join(self.out, name)
                if os.path.exists(stale):
                    os.remove(stale)
        if extend or not os.path.exists(path):
            _write_json(path, settings.to_json())

    def _check_members(self):
        """Every member of both populations, before any training: a batch that plays it refuses an unknown player,
        a player or file of the other role, a file of another observation (peg3d.InputError naming the member)."""
        s = self.settings
        for r in ROLES:
            for k, member in enumerate(getattr(s, r + "s")):
                try:
                    VectorEnv(num_envs=1, opponents={r: member}, **_env_keywords(s)).close()
                except _core.InputError as e:
                    raise _core.InputError(f"{r}s.{k}: {member}: {e}") from None
        if s.facl_episodes > 0:
            # The FACL learners' settings, as their training reads them.
            for r in ROLES:
                try:
                    VectorEnv(num_envs=1, **dict(_env_keywords(s), set=_facl_sets(s, r))).close()
                except _core.InputError as e:
                    raise _core.InputError(f"facl_set: {e}") from None

    # ---- state ----
    def _state_path(self, k):
        return os.path.join(self.out, f"iteration_{k}", "state.json")

    def _last_state(self):
        k, state = 0, None
        while os.path.exists(self._state_path(k)):
            with open(self._state_path(k)) as f:
                state = json.load(f)
            k += 1
        return state

    def _evaluate(self, members, payoffs):
        """Fills payoffs[(i, j)] for every pairing of members["pursuer"] x members["evader"] not yet played."""
        s = self.settings
        seed = derive_seed(s.seed, "evaluation")  # the same held-out seeds for every pairing
        todo = [(i, j) for i in range(len(members["pursuer"])) for j in range(len(members["evader"]))
                if f"{i},{j}" not in payoffs]
        calls = [(s, _absolute(members["pursuer"][i], self.out), _absolute(members["evader"][j], self.out),
                  s.eval_games, seed) for i, j in todo]
        for (i, j), r in zip(todo, self.runner.map("play", calls)):
            payoffs[f"{i},{j}"] = r

    @staticmethod
    def _matrix(members, payoffs, key="payoff"):
        return np.array([[payoffs[f"{i},{j}"][key] for j in range(len(members["evader"]))]
                         for i in range(len(members["pursuer"]))])

    def run(self):
        s = self.settings
        state = self._last_state()
        if state is None:
            state = {"iteration": -1, "members": {"pursuer": [str(m) for m in s.pursuers],
                                                   "evader": [str(m) for m in s.evaders]},
                     "payoffs": {}, "history": []}
        else:
            self.log(f"resuming after iteration {state['iteration']} of {s.iterations}")
        members, payoffs = state["members"], state["payoffs"]
        for k in range(state["iteration"] + 1, s.iterations):
            start = time.time()
            self._evaluate(members, payoffs)
            m = self._matrix(members, payoffs)
            x, y, low, high = solve_zero_sum(m, s.solver_iterations)
            # Each role's best responses train against these opponents (the other role's members).
            league = league_weights(self._matrix(members, payoffs, "capture_rate"), x, y, s.league_share)
            mixtures = {r: _mixture(members[other_role(r)], league[r], self.out) for r in ROLES}
            folder = os.path.join(self.out, f"iteration_{k}")
            os.makedirs(folder, exist_ok=True)
            calls = [(s, r, mixtures[r], s.budget_of(r), derive_seed(s.seed, "train", k, r))
                     for r in ROLES]
            trained = {}
            for r, net in zip(ROLES, self.runner.map("train", calls)):
                name = f"iteration_{k}/{r}.json"
                net.save(os.path.join(self.out, name), trained_by="peg3d.selfplay", iteration=k,
                         opponents=sorted(mixtures[r]))
                trained[r] = {"file": name, "history": net.history}
            if s.facl_episodes > 0:
                # The paper's learner against the same mixtures, from files the C++ side reads.
                calls = []
                for r in ROLES:
                    o = other_role(r)
                    mixture = os.path.join(folder, f"{o}_mixture.json")
                    _write_mixture(mixture, o, members[o], league[r], self.out)
                    calls.append((s, r, os.path.abspath(mixture), s.facl_episodes, derive_seed(s.seed, "facl", k, r)))
                for r, text in zip(ROLES, self.runner.map("train_facl", calls)):
                    name = f"iteration_{k}/{r}_facl.json"
                    with open(os.path.join(self.out, name), "w") as f:
                        f.write(text)
                    trained[r]["facl"] = name
            entry = {"iteration": k, "pursuer_mixture": x.tolist(), "evader_mixture": y.tolist(),
                     "value": [low, high], "members": {r: len(members[r]) for r in ROLES},
                     "trained": trained}
            if s.league_share > 0:
                entry["opponents"] = {r: league[r].tolist() for r in ROLES}
            for r in ROLES:
                members[r].append(trained[r]["file"])
                if "facl" in trained[r]:
                    members[r].append(trained[r]["facl"])
            state = {"iteration": k, "members": members, "payoffs": payoffs, "history": state["history"] + [entry]}
            _write_json(self._state_path(k), state)
            line = json.dumps({"iteration": k, "value": [low, high], "pursuers": len(members["pursuer"]),
                               "evaders": len(members["evader"]), "seconds": round(time.time() - start, 2)})
            # Wall-clock times go to the log alone: every other file is the seed's, the same on any machine.
            with open(os.path.join(self.out, "log.jsonl"), "a") as f:
                f.write(line + "\n")
            self.log(line)
        return self._finish(state)

    def _finish(self, state):
        """The final matrix and mixtures, the exploitability curve and a fresh best response per role."""
        s = self.settings
        members, payoffs = state["members"], state["payoffs"]
        self._evaluate(members, payoffs)
        m = self._matrix(members, payoffs)
        x, y, low, high = solve_zero_sum(m, s.solver_iterations)
        # The curve: each iteration's mixtures against every member the run made (a lower bound of their
        # exploitability: max over pursuers of the payoff against the evaders' mixture, less the min over evaders).
        curve = []
        for h in state["history"] + [{"iteration": s.iterations, "pursuer_mixture": x.tolist(),
                                      "evader_mixture": y.tolist(), "members": {r: len(members[r]) for r in ROLES}}]:
            px, ey = np.array(h["pursuer_mixture"]), np.array(h["evader_mixture"])
            p, e = h["members"]["pursuer"], h["members"]["evader"]
            best_p = float((m[:, :e] @ ey).max())
            best_e = float((px @ m[:p, :]).min())
            curve.append({"iteration": h["iteration"], "exploitability": best_p - best_e,
                          "pursuer_best_response": best_p, "evader_best_response": best_e})
        final = {"pursuer": _mixture(members["pursuer"], x, self.out), "evader": _mixture(members["evader"], y, self.out)}
        fresh_path = os.path.join(self.out, EXPLOITABILITY)
        if os.path.exists(fresh_path):
            with open(fresh_path) as f:
                fresh = json.load(f)
        else:
            calls = [(s, r, final[other_role(r)], s.budget_of(r, final=True), derive_seed(s.seed, "exploit", r))
                     for r in ROLES]
            fresh = {}
            for r, net in zip(ROLES, self.runner.map("train", calls)):
                name = BEST_RESPONSE.format(r)
                net.save(os.path.join(self.out, name), trained_by="peg3d.selfplay (exploitability)",
                         opponents=sorted(final[other_role(r)]))
                fresh[r] = name
            seed = derive_seed(s.seed, "evaluation")
            plays = self.runner.map("play", [
                (s, _absolute(fresh["pursuer"], self.out), final["evader"], s.eval_games, seed),
                (s, final["pursuer"], _absolute(fresh["evader"], self.out), s.eval_games, seed)])
            # The best known response of each role: the fresh one, or a member that does better against the mixture
            # (a short training can fall behind the members); exploitability = what they gain, >= high - low.
            best_p = max(plays[0]["payoff"], float((m @ y).max()))
            best_e = min(plays[1]["payoff"], float((x @ m).min()))
            fresh = {"files": fresh, "pursuer_best_response": plays[0], "evader_best_response": plays[1],
                     "best_pursuer_payoff": best_p, "best_evader_payoff": best_e, "exploitability": best_p - best_e}
            _write_json(fresh_path, fresh)
        # The final mixtures as policy files the C++ side plays (peg-league --pursuer-entrant NAME=FILE, peg-matchup,
        # opponents=): one member drawn per episode, members named relative to the run's folder.
        for r, weights in (("pursuer", x), ("evader", y)):
            _write_mixture(os.path.join(self.out, FINAL.format(r)), r, members[r], weights, self.out)
        summary = {"members": members, "payoff": m.tolist(),
                   "capture_rate": self._matrix(members, payoffs, "capture_rate").tolist(),
                   "pursuer_mixture": x.tolist(), "evader_mixture": y.tolist(), "value": [low, high],
                   "curve": curve, "fresh_best_responses": fresh}
        _write_json(os.path.join(self.out, SUMMARY), summary)
        return summary


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m peg3d.selfplay", description=__doc__.splitlines()[0])
    d = Settings()
    ap.add_argument("--map", default=d.map)
    ap.add_argument("--scenario", action="append", help="a start of the map; repeat for several")
    ap.add_argument("--set", action="append", default=[], help="configuration override key=value")
    ap.add_argument("--neighbours", type=int, default=d.neighbours)
    ap.add_argument("--pursuer", action="append", help="a first member of the pursuers' population (a player or a "
                    f"policy file); repeat (default: {','.join(d.pursuers)})")
    ap.add_argument("--evader", action="append", help=f"likewise for the evaders (default: {','.join(d.evaders)})")
    ap.add_argument("--iterations", type=int, default=d.iterations)
    ap.add_argument("--steps", type=int, default=d.budget.steps, help="env steps of each best response's training")
    for r in ROLES:
        ap.add_argument(f"--{r}-steps", type=int, help=f"env steps of each {r} best response (default: --steps)")
    ap.add_argument("--final-steps", type=int, help="env steps of the exploitability's best responses, both roles "
                    "(default: each role's)")
    ap.add_argument("--num-envs", type=int, default=d.budget.num_envs)
    ap.add_argument("--rollout", type=int, default=d.budget.rollout)
    ap.add_argument("--threads", type=int, default=1, help="C++ threads for training and evaluation")
    ap.add_argument("--facl-episodes", type=int, default=d.facl_episodes,
                    help="episodes of each FACL best response (one per role and iteration; 0: none)")
    ap.add_argument("--facl-set", action="append", default=[],
                    help="a FACL learner's setting key=value under its role (default: observation.sight_inputs=true)")
    ap.add_argument("--league-share", type=float, default=d.league_share,
                    help="share of each best response's opponents drawn from the other role's whole population by "
                    "prioritised fictitious self-play, in [0, 1) (default 0: the meta-game's mixture alone)")
    ap.add_argument("--eval-games", type=int, default=d.eval_games)
    ap.add_argument("--seed", type=int, default=d.seed)
    ap.add_argument("--out", required=True)
    ap.add_argument("--resume", action="store_true", help="continue the run in --out from its last finished iteration (a larger --iterations extends it)")
    ap.add_argument("--ray", metavar="ADDRESS", help="run evaluations and trainings as tasks of this Ray cluster")
    a = ap.parse_args(argv)
    try:
        sets = dict(d.set, **dict(kv.split("=", 1) for kv in a.set))
        facl_set = dict(d.facl_set, **dict(kv.split("=", 1) for kv in a.facl_set))
    except ValueError:
        ap.error("--set and --facl-set: key=value")
    budget = Budget(steps=a.steps, num_envs=a.num_envs, rollout=a.rollout, threads=a.threads)
    role_steps = {r: getattr(a, f"{r}_steps") for r in ROLES if getattr(a, f"{r}_steps") is not None}
    settings = Settings(map=a.map, scenario=a.scenario, set=sets, neighbours=a.neighbours,
                        pursuers=a.pursuer or d.pursuers, evaders=a.evader or d.evaders, iterations=a.iterations,
                        budget=budget, role_steps=role_steps, final_budget=None if a.final_steps is None else dataclasses.replace(budget, steps=a.final_steps),
                        facl_episodes=a.facl_episodes, facl_set=facl_set, league_share=a.league_share,
                        eval_games=a.eval_games,
                        eval_threads=a.threads, seed=a.seed)
    try:
        summary = SelfPlay(settings, a.out, resume=a.resume, ray_address=a.ray).run()
    except (ValueError, TypeError, FileExistsError, ConnectionError, ImportError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    fresh = summary["fresh_best_responses"]
    print(json.dumps({"value": summary["value"], "exploitability": fresh["exploitability"],
                      "summary": os.path.join(a.out, SUMMARY)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
