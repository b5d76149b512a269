"""peg3d.selfplay: the meta-game solver against analytic equilibria, the payoffs of pairings played on the C++ side,
and two tiny iterations: their files, the same results from the same seed, and a resumed run equal to one never
stopped. Training runs are not tests: the budgets here are seconds."""

import csv
import filecmp
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import peg3d
from peg3d import selfplay
from conftest import BIN
from peg3d.mappo import Budget

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("matrix, x, y, value", [
    ([[1, 0], [0, 1]], [0.5, 0.5], [0.5, 0.5], 0.5),                        # matching pennies, shifted
    ([[0.5, 0, 1], [1, 0.5, 0], [0, 1, 0.5]], [1 / 3] * 3, [1 / 3] * 3, 0.5),  # rock-paper-scissors
    ([[0.9, 0.6], [0.3, 0.2]], [1, 0], [0, 1], 0.6),                        # a saddle point: row 0, column 1
    ([[0.2, 0.8], [0.6, 0.4]], [0.25, 0.75], [0.5, 0.5], 0.5),              # mixed, unequal weights
])
def test_fictitious_play_finds_the_equilibrium(matrix, x, y, value):
    gx, gy, low, high = selfplay.solve_zero_sum(matrix, 20000)
    assert low <= value + 1e-12 and value - 1e-12 <= high
    assert high - low < 0.01
    assert np.allclose(gx, x, atol=0.02) and np.allclose(gy, y, atol=0.02)


def test_the_solver_refuses_what_is_not_a_matrix():
    for bad in ([], [[np.nan]], [1, 2]):
        with pytest.raises(ValueError, match="matrix"):
            selfplay.solve_zero_sum(bad)


def test_a_pairing_is_played_by_both_sides_on_the_cpp_side():
    # A standing evader (speed 0) is caught by pure pursuit in every game; early catches pay the tie-break.
    s = selfplay.Settings(map="maps/paper.yaml", set={"time_limit": 60.0, "evader.speed": 0.0})
    r = selfplay.play_pairing(s, "pure-pursuit", "flee", 6, 5)
    assert r["games"] == 6 and r["capture_rate"] == 1.0
    assert 1.0 < r["payoff"] <= 1.0 + selfplay.TIE_BREAK
    assert selfplay.play_pairing(s, "pure-pursuit", "flee", 6, 5) == r  # the seed decides
    slow = selfplay.Settings(map="maps/paper.yaml", set={"time_limit": 1.0})
    r = selfplay.play_pairing(slow, "pure-pursuit", "flee", 4, 5)
    assert r["capture_rate"] == 0.0 and r["payoff"] == 0.0 and r["mean_steps"] == 10


def tiny(**kw):
    settings = dict(map="maps/paper.yaml", set={"time_limit": 3.0, "initial_heading": "random"}, pursuers=["pure-pursuit", "pn"],
                    evaders=["flee", "random"], iterations=2, eval_games=4, solver_iterations=500,
                    budget=Budget(steps=256, num_envs=4, rollout=32), seed=3)
    return selfplay.Settings(**{**settings, **kw})


def run(out, **kw):
    return selfplay.SelfPlay(tiny(), out, log=lambda *_: None, **kw).run()


def run_files(folder):
    """Every file a run wrote, relative to its folder, sorted."""
    return sorted(os.path.relpath(os.path.join(r, f), folder) for r, _, fs in os.walk(folder) for f in fs)


def test_two_tiny_iterations_write_their_files_and_repeat_from_the_seed(tmp_path):
    pytest.importorskip("torch")
    a = run(tmp_path / "a")
    files = run_files(tmp_path / "a")
    assert files == ["best_response_evader.json", "best_response_pursuer.json", "exploitability.json",
                     "final_evader.json", "final_pursuer.json", "iteration_0/evader.json", "iteration_0/pursuer.json", "iteration_0/state.json",
                     "iteration_1/evader.json", "iteration_1/pursuer.json", "iteration_1/state.json",
                     "log.jsonl", "settings.json", "summary.json"]
    # What an extension removes is every file the ending wrote: the top-level files but the run's settings and log.
    assert sorted(selfplay.ENDING) == [f for f in files if "/" not in f and f not in ("log.jsonl", "settings.json")]
    assert a["members"]["pursuer"] == ["pure-pursuit", "pn", "iteration_0/pursuer.json", "iteration_1/pursuer.json"]
    assert np.array(a["payoff"]).shape == (4, 4)
    assert len(a["curve"]) == 3 and all(c["exploitability"] >= -1e-12 for c in a["curve"])
    assert abs(sum(a["pursuer_mixture"]) - 1) < 1e-9
    low, high = a["value"]
    assert a["fresh_best_responses"]["exploitability"] >= high - low - 1e-12
    # A trained network plays in C++ as any policy file: against a mixture of the classic evaders.
    net = peg3d.read_policy(tmp_path / "a" / "iteration_1" / "evader.json")
    assert net["role"] == "evader"
    # The final mixtures read back from Python too: their members, weights and the networks' documents.
    final = peg3d.read_policy(tmp_path / "a" / "final_pursuer.json")
    assert final["format"] == peg3d.MIXTURE_FORMAT and final["role"] == "pursuer"
    weights = {m["policy"]: m["weight"] for m in final["members"]}
    assert abs(sum(weights.values()) - 1) < 1e-9
    for m in final["members"]:
        assert (m["document"] is None) == (m["policy"] in ("pure-pursuit", "pn"))
        if m["document"] is not None:
            assert m["document"] == peg3d.read_policy(m["path"])
    # The final mixtures play in the C++ programs and as opponents: peg-league's entrants, a batch's opponents.
    out = tmp_path / "league"
    league = subprocess.run([str(BIN / "peg-league"), "--map", "maps/paper.yaml", "--algorithms", "baseline",
                             "--train-seeds", "1", "--eval-seeds", "2", "--episodes", "1", "--no-plots", "--plain-progress",
                             "--no-cache", "--set", "time_limit=3", "--out", str(out),
                             "--pursuer-entrant", f"final={tmp_path / 'a' / 'final_pursuer.json'}",
                             "--evader-entrant", f"final={tmp_path / 'a' / 'final_evader.json'}"],
                            cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert league.returncode == 0, league.stderr[-800:]
    with open(out / "games.csv") as f:
        games = list(csv.DictReader(f))
    assert any(g["pursuer"] == "final" and g["evader"] == "final" for g in games)
    env = peg3d.vector_env(map="maps/paper.yaml", num_envs=2, set={"time_limit": 3.0},
                           opponents={"evader": str(tmp_path / "a" / "final_evader.json")})
    env.reset(seed=1)
    assert env.controlled["evader"].all()
    # The figure of docs/learning.md is drawn from the summary.
    plot = subprocess.run(["/usr/bin/python3", str(ROOT / "tools/plot_selfplay.py"), str(tmp_path / "a")],
                          capture_output=True, text=True, timeout=300)
    assert plot.returncode == 0, plot.stderr
    assert (tmp_path / "a" / "selfplay.png").stat().st_size > 10000
    os.remove(tmp_path / "a" / "selfplay.png")
    b = run(tmp_path / "b")
    assert a == b
    for name in files:
        if name != "log.jsonl":  # wall-clock times
            assert filecmp.cmp(tmp_path / "a" / name, tmp_path / "b" / name, shallow=False), name


def test_a_run_stopped_after_an_iteration_resumes_as_if_never_stopped(tmp_path):
    pytest.importorskip("torch")
    whole = run(tmp_path / "whole")
    shutil.copytree(tmp_path / "whole", tmp_path / "stopped")
    # As if stopped during iteration 1: its files half written, no record of it.
    for name in ("iteration_1/state.json", "summary.json", "exploitability.json", "best_response_pursuer.json",
                 "best_response_evader.json"):
        os.remove(tmp_path / "stopped" / name)
    with open(tmp_path / "stopped" / "iteration_1" / "pursuer.json", "w") as f:
        f.write("{")
    with pytest.raises(FileExistsError, match="resume"):
        run(tmp_path / "stopped")
    assert run(tmp_path / "stopped", resume=True) == whole
    other = tiny()
    other.seed = 4
    with pytest.raises(ValueError, match="seed"):
        selfplay.SelfPlay(other, tmp_path / "stopped", resume=True)


def test_a_finished_run_resumed_with_more_iterations_is_the_longer_run(tmp_path):
    pytest.importorskip("torch")
    whole = run(tmp_path / "whole")  # two iterations
    short = selfplay.SelfPlay(tiny(iterations=1), tmp_path / "extended", log=lambda *_: None).run()
    assert short != whole
    with pytest.raises(ValueError, match="iterations 1 would drop"):
        selfplay.SelfPlay(tiny(iterations=1), tmp_path / "whole", resume=True)
    assert run(tmp_path / "extended", resume=True) == whole
    assert run_files(tmp_path / "extended") == run_files(tmp_path / "whole")
    for name in run_files(tmp_path / "whole"):
        if name != "log.jsonl":  # wall-clock times
            assert filecmp.cmp(tmp_path / "whole" / name, tmp_path / "extended" / name, shallow=False), name


@pytest.mark.parametrize("change, error, message", [
    ({"pursuers": ["pure-pursuit", "no-such-player"]}, peg3d.InputError, r"pursuers\.1"),
    ({"evaders": ["flee", "pn"]}, peg3d.InputError, r"evaders\.1"),
    ({"evaders": []}, ValueError, "evaders: at least one"),
    ({"iterations": 0}, ValueError, "iterations"),
    ({"budget": Budget(steps=0)}, ValueError, "budget.steps"),
    ({"role_steps": {"seeker": 512}}, ValueError, "role_steps: 'seeker'"),
    ({"role_steps": {"evader": 0}}, ValueError, "role_steps.evader"),
    ({"league_share": 1.0}, ValueError, r"league_share: a number in \[0, 1\), not 1.0"),
    ({"league_share": -0.1}, ValueError, "league_share"),
    ({"league_share": "0.5"}, ValueError, "league_share"),
])
def test_bad_settings_are_refused_before_any_training(tmp_path, change, error, message):
    s = tiny()
    for k, v in change.items():
        setattr(s, k, v)
    with pytest.raises(error, match=message):
        selfplay.SelfPlay(s, tmp_path / "run")
    assert not (tmp_path / "run").exists()


def test_each_role_trains_its_own_steps(tmp_path):
    pytest.importorskip("torch")
    s = tiny(iterations=1, role_steps={"evader": 512})
    assert s.budget_of("pursuer").steps == 256 and s.budget_of("evader").steps == 512
    assert s.budget_of("evader", final=True).steps == 512  # the fresh best response as the role's
    assert tiny(role_steps={"evader": 512}, final_budget=Budget(steps=64)).budget_of("evader", final=True).steps == 64
    selfplay.SelfPlay(s, tmp_path / "run", log=lambda *_: None).run()
    with open(tmp_path / "run" / "iteration_0" / "state.json") as f:
        trained = json.load(f)["history"][0]["trained"]
    # An update takes num_envs x rollout = 128 env steps; the history counts them.
    assert trained["pursuer"]["history"][-1]["steps"] == 256
    assert trained["evader"]["history"][-1]["steps"] == 512
    with open(tmp_path / "run" / "settings.json") as f:
        assert json.load(f)["role_steps"] == {"evader": 512}


def test_a_policy_file_of_the_other_role_is_refused_naming_it(tmp_path):
    file = os.path.join(os.path.dirname(__file__), "..", "data", "policies", "robust_evader.json")
    s = tiny()
    s.pursuers = ["pn", file]
    with pytest.raises(peg3d.InputError, match="robust_evader.json"):
        selfplay.SelfPlay(s, tmp_path / "run")


def test_the_command_line_exits_2_on_bad_input(tmp_path, capsys):
    assert selfplay.main(["--out", str(tmp_path / "x"), "--pursuer", "nobody", "--map", "maps/paper.yaml"]) == 2
    assert "nobody" in capsys.readouterr().err


def test_facl_best_responses_trained_in_cpp_join_the_populations(tmp_path):
    pytest.importorskip("torch")
    s = tiny(facl_episodes=3)
    a = selfplay.SelfPlay(s, tmp_path / "a", log=lambda *_: None).run()
    assert a["members"]["pursuer"] == ["pure-pursuit", "pn", "iteration_0/pursuer.json", "iteration_0/pursuer_facl.json",
                                       "iteration_1/pursuer.json", "iteration_1/pursuer_facl.json"]
    assert a["members"]["evader"][-1] == "iteration_1/evader_facl.json"
    assert np.array(a["payoff"]).shape == (6, 6)
    # A FACL file: the learners' settings, the sight entries among its inputs.
    with open(tmp_path / "a" / "iteration_1" / "pursuer_facl.json") as f:
        doc = json.load(f)
    assert doc["role"] == "pursuer" and doc["config"]["policy"] == "facl"
    assert doc["config"]["observation"]["sight_inputs"] is True
    # Each FACL response trained against the mixture of its iteration, written beside it (files named from there).
    with open(tmp_path / "a" / "iteration_1" / "state.json") as f:
        state = json.load(f)
    weights = state["history"][1]["evader_mixture"]
    mixture = peg3d.read_policy(tmp_path / "a" / "iteration_1" / "evader_mixture.json")
    named = ["flee", "random", "../iteration_0/evader.json", "../iteration_0/evader_facl.json"]
    assert [m["policy"] for m in mixture["members"]] == [n for n, w in zip(named, weights) if w > 0]
    # The C++ training is a pure function of its seed.
    file = str(tmp_path / "a" / "iteration_1" / "evader_mixture.json")
    one = selfplay._train_facl(s, "pursuer", file, 2, 7)
    assert selfplay._train_facl(s, "pursuer", file, 2, 7) == one
    assert selfplay._train_facl(s, "pursuer", file, 2, 8) != one
    # Bad FACL settings are refused before any training.
    bad = tiny(facl_episodes=3, facl_set={"observation.no_such": "1"})
    with pytest.raises(peg3d.InputError, match="facl_set.*no_such"):
        selfplay.SelfPlay(bad, tmp_path / "bad")
    assert not (tmp_path / "bad").exists()


def test_a_mixture_file_names_its_members_where_the_cpp_loader_finds_them(tmp_path):
    # The run's files relative to the mixture's folder; a first member given relative to the working folder by its
    # absolute path; players by name. The C++ loader reads every one (a wrong path is an InputError).
    robust = os.path.join(os.path.dirname(__file__), "..", "data", "policies", "robust_evader.json")
    (tmp_path / "iteration_0").mkdir()
    shutil.copy(robust, tmp_path / "iteration_0" / "evader.json")
    (tmp_path / "iteration_1").mkdir()
    mixture = tmp_path / "iteration_1" / "evader_mixture.json"
    selfplay._write_mixture(str(mixture), "evader", ["flee", os.path.relpath(robust), "iteration_0/evader.json", "random"],
                            [0.5, 0.25, 0.25, 0.0], str(tmp_path))
    doc = peg3d.read_policy(mixture)  # checked by the C++ loader
    assert [m["policy"] for m in doc["members"]] == ["flee", os.path.abspath(robust), "../iteration_0/evader.json"]
    assert [m["weight"] for m in doc["members"]] == [0.5, 0.25, 0.25]


def test_league_weights_mix_the_equilibrium_with_prioritised_fictitious_self_play():
    rate = np.array([[1.0, 0.5],   # pursuers down, evaders across
                     [0.0, 0.0]])
    x, y = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    assert all(np.array_equal(w, m) for w, m in zip(selfplay.league_weights(rate, x, y, 0).values(), (y, x)))
    w = selfplay.league_weights(rate, x, y, 0.5)
    # The evaders' learner: pursuer 0 catches the evaders' mixture in 0.5, pursuer 1 never: PFSP 1 : 0.
    assert np.allclose(w["evader"], 0.5 * x + 0.5 * np.array([1.0, 0.0]))
    # The pursuers' learner: evader 0 never escapes the pursuers' mixture, evader 1 in 0.5: PFSP 0 : 1.
    assert np.allclose(w["pursuer"], 0.5 * y + 0.5 * np.array([0.0, 1.0]))
    # No evader escapes: the league part is uniform.
    w = selfplay.league_weights(np.ones((2, 2)), x, y, 0.2)
    assert np.allclose(w["pursuer"], 0.8 * y + 0.2 * np.array([0.5, 0.5]))
    rate = np.array([[0.9, 0.6], [0.3, 0.2]])
    w = selfplay.league_weights(rate, x, y, 0.5)["evader"]
    assert np.allclose(w, 0.5 * x + 0.5 * np.array([0.36, 0.04]) / 0.40)


def test_a_league_run_trains_against_the_weights_it_records(tmp_path):
    pytest.importorskip("torch")
    selfplay.SelfPlay(tiny(league_share=0.5, facl_episodes=2), tmp_path, log=lambda *_: None).run()
    with open(tmp_path / "iteration_1" / "state.json") as f:
        state = json.load(f)
    entry = state["history"][1]
    n = entry["members"]
    rate = np.array([[state["payoffs"][f"{i},{j}"]["capture_rate"] for j in range(n["evader"])]
                     for i in range(n["pursuer"])])
    want = selfplay.league_weights(rate, entry["pursuer_mixture"], entry["evader_mixture"], 0.5)
    for r in selfplay.ROLES:
        assert np.allclose(entry["opponents"][r], want[r])
        assert entry["opponents"][r] != entry[f"{selfplay.other_role(r)}_mixture"]
    # The FACL learner of the pursuers read the same weights from its mixture file.
    with open(tmp_path / "iteration_1" / "evader_mixture.json") as f:
        written = [m["weight"] for m in json.load(f)["members"]]
    assert np.allclose(written, [w for w in want["pursuer"] if w > 0])
    # The network's record names the members it trained against: the whole population, not the mixture alone.
    with open(tmp_path / "iteration_1" / "evader.json") as f:
        assert len(json.load(f)["opponents"]) == sum(w > 0 for w in want["evader"])
