"""tools/near_equilibria.py on a meta-game small enough to solve by hand."""

import json
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "near_equilibria.py"

# Pursuers down (strong catches everything, pn and other have different weaknesses), evaders a, b, c across.
RATE = [[1.00, 0.99, 0.97],
        [0.90, 0.50, 0.80],
        [0.10, 0.90, 0.10]]


def tool(tmp_path, *args, payoff=RATE):
    run = tmp_path / "run"
    run.mkdir(exist_ok=True)
    (run / "summary.json").write_text(json.dumps({
        "members": {"pursuer": ["strong", "pn", "other"], "evader": ["a", "b", "c"]},
        "payoff": payoff, "capture_rate": RATE}))
    return subprocess.run(["/usr/bin/python3", str(TOOL), str(run), *args], capture_output=True, text=True,
                          timeout=120)


def entries(tmp_path, *args):
    r = tool(tmp_path, "--json", *args)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_margins_widen_the_evaders_choice_as_solved_by_hand(tmp_path):
    d = entries(tmp_path, "--eps", "0", "0.01", "0.02")
    assert d["value"] == pytest.approx(0.97)  # strong's row: c is its least caught
    at0, at1, at2 = d["entries"]
    # Within 0: the equilibrium's c alone, by either measure.
    for name in ("against", "population"):
        assert at0[name]["mixture"] == {"c": 1.0}
        assert at0[name]["capture_rate_by_pn"] == pytest.approx(0.80)
    # Within 0.01: strong may catch 0.98, so b up to half (0.99 b + 0.97 (1 - b) <= 0.98): pn 0.65.
    assert at1["against"]["mixture"] == pytest.approx({"b": 0.5, "c": 0.5}, abs=1e-4)
    assert at1["against"]["capture_rate_by_pn"] == pytest.approx(0.65, abs=1e-6)
    # Within 0.02: b alone (pn 0.5); on average over the three pursuers c stays best (0.623 against b's 0.797).
    assert at2["against"]["mixture"] == {"b": 1.0}
    assert at2["against"]["capture_rate_by_pn"] == pytest.approx(0.50, abs=1e-6)
    assert at2["population"]["mixture"] == {"c": 1.0}
    assert at2["population"]["capture_rate_mean"] == pytest.approx((0.97 + 0.80 + 0.10) / 3)


def test_the_pursuers_side_is_the_same_problem_turned_round(tmp_path):
    d = entries(tmp_path, "--role", "pursuer", "--against", "b", "--eps", "0")
    assert d["value"] == pytest.approx(0.97)
    assert d["entries"][0]["against"]["mixture"] == {"strong": 1.0}
    assert d["entries"][0]["against"]["capture_rate_by_b"] == pytest.approx(0.99)


def test_bad_input_is_refused_with_its_name(tmp_path):
    r = tool(tmp_path, "--against", "pm")
    assert r.returncode == 2 and "'pm' is not a member of the pursuers" in r.stderr
    r = tool(tmp_path, payoff=[[1.0, 0.5]])
    assert r.returncode == 2 and "3 x 3" in r.stderr
    r = subprocess.run(["/usr/bin/python3", str(TOOL), str(tmp_path / "missing")], capture_output=True, text=True)
    assert r.returncode == 2 and "summary.json" in r.stderr
