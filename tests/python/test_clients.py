"""The field's clients, unmodified, on peg3d's registered ids: Stable-Baselines3's PPO (its env checker, its
make_vec_env, a short training) and the CleanRL-style script examples/cleanrl_ppo.py on gymnasium.make_vec.
Short smoke runs; the long runs and their learning curves are in docs/python.md."""

import csv
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import peg3d  # noqa: F401 - registers the ids

SOURCE = Path(__file__).resolve().parents[2]
KWARGS = {"map": "maps/paper.yaml", "set": {"time_limit": 20.0}}


def test_stable_baselines3_checks_and_trains_the_registered_pursuer(tmp_path, monkeypatch):
    monkeypatch.setenv("SB3_LOGDIR", str(tmp_path))  # SB3's logger makes a folder, by default one more in /tmp per run
    pytest.importorskip("stable_baselines3")  # in .venv; not in the clean environments of tools/test.sh --python-versions
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_checker import check_env
    from stable_baselines3.common.env_util import make_vec_env

    check_env(gym.make("peg3d/Pursuer-v0", **KWARGS).unwrapped, warn=False)
    venv = make_vec_env("peg3d/Pursuer-v0", n_envs=2, seed=0, env_kwargs=KWARGS)
    model = PPO("MlpPolicy", venv, n_steps=256, batch_size=64, n_epochs=2, seed=0, device="cpu")
    model.learn(2048)
    assert model.num_timesteps == 2048
    logged = model.logger.name_to_value
    # 2048 steps of 2 games x 256: 4 rollouts, 2 epochs each
    assert logged["train/n_updates"] == 8 and math.isfinite(logged["train/loss"])
    action, _ = model.predict(venv.reset(), deterministic=True)
    assert action.shape == (2, 2)


def test_the_cleanrl_style_script_runs_by_environment_id(tmp_path):
    pytest.importorskip("torch")
    log = tmp_path / "curve.csv"
    kwargs = dict(KWARGS, threads=2)
    out = subprocess.run([sys.executable, str(SOURCE / "examples" / "cleanrl_ppo.py"), "--env-id", "peg3d/Pursuer-v0",
                          "--env-kwargs", json.dumps(kwargs), "--total-timesteps", "8192", "--num-envs", "8",
                          "--num-steps", "256", "--update-epochs", "2", "--log", str(log)],
                         check=True, capture_output=True, text=True, env=dict(os.environ), timeout=600).stdout
    lines = [json.loads(line) for line in out.splitlines()]
    assert [x["env_steps"] for x in lines] == [2048, 4096, 6144, 8192]
    assert all(math.isfinite(x["loss"]) for x in lines)
    assert lines[-1]["episodes"] >= 8  # 20 s episodes: every game ended at least once in 1 024 steps each
    with open(log, newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 4 and np.isfinite(float(rows[-1]["mean_return"]))
