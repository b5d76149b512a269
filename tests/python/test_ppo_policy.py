"""The PPO pursuer: a short training run (smoke), and the shipped trained network played by the C++ side
(players/mlp_policy.hpp) and by a Python reference of the documented forward pass, with the same games."""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import peg3d

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = ROOT / "tests/data/policies/ppo_pursuer.json"


def forward(doc, x):
    """docs/python.md's forward pass: every sum in double, over the inputs in order."""
    a = [(float(v) - m) * (1.0 / s) for v, m, s in zip(x, doc["input_mean"], doc["input_std"])]
    for k, layer in enumerate(doc["layers"]):
        out = []
        for row, b in zip(layer["weights"], layer["bias"]):
            s = b
            for w, v in zip(row, a):
                s += w * v
            out.append(s if k + 1 == len(doc["layers"]) else math.tanh(s))
        a = out
    return np.array([doc["action_bound"] * math.tanh(a[0]), doc["action_bound"] * math.tanh(a[1])])


def test_a_short_ppo_run_trains_and_saves_a_policy_the_cpp_side_plays(tmp_path):
    pytest.importorskip("torch")
    out = tmp_path / "ppo.json"
    run = subprocess.run([sys.executable, str(ROOT / "examples/ppo_pursuer.py"), "--steps", "4096", "--num-envs", "8",
                          "--rollout", "64", "--threads", "2", "--out", str(out), "--opponent", "flee",
                          "--opponent", str(ROOT / "tests/data/policies/robust_evader.json")], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr
    doc = json.loads(out.read_text())
    assert doc["format"] == "peg3d-mlp" and doc["inputs"] == 20
    assert doc["opponents"] == ["flee", str(ROOT / "tests/data/policies/robust_evader.json")]
    # the Gaussian's learnt standard deviation, near its start of half the bound after 4 096 steps; played by its mean
    assert len(doc["action_std"]) == 2 and all(0.3 < s / doc["action_bound"] < 0.7 for s in doc["action_std"])
    assert doc["play"] == "mean"
    v = peg3d.vector_env(num_envs=2, opponents={"pursuer": str(out), "evader": "flee"}, neighbours=0,
                         set={"time_limit": 2.0})
    v.reset(seed=0)
    for _ in range(25):
        v.step({})
    assert v._batch.episode(0) >= 1  # a 2 s episode of 20 steps ended and restarted


def play(opponents, policy=None, steps=1000):
    v = peg3d.vector_env(map="maps/paper.yaml", num_envs=1, opponents=opponents, neighbours=0,
                         set={"initial_heading": "random"}, seed=21)
    obs, _ = v.reset(seed=21)
    states = [v._batch.agent_states(0)]
    for _ in range(steps):
        if policy is None:
            obs, rew, term, trunc, info = v.step({})
        else:
            obs, rew, term, trunc, info = v.step({"pursuer": forward(policy, obs["pursuer"][0, 0])[None, None, :]})
        if info["reset"][0]:
            break
        states.append(v._batch.agent_states(0))
        if term["pursuer"][0, 0] or trunc["pursuer"][0, 0]:
            break
    return np.array(states), v._batch.game_info(0)


def test_the_shipped_network_plays_the_same_game_in_cpp_and_in_python():
    doc = json.loads(FIXTURE.read_text())
    cpp, cpp_info = play({"pursuer": str(FIXTURE), "evader": "flee"})
    ref, ref_info = play({"evader": "flee"}, policy=doc)
    assert len(cpp) > 20
    assert cpp.shape == ref.shape
    np.testing.assert_array_equal(cpp, ref)
    assert cpp_info == ref_info
