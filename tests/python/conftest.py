"""The peg3d package from build/python (tests/CMakeLists.txt sets PYTHONPATH, and runs them in .venv, where
gymnasium and pettingzoo are). By hand: PYTHONPATH=build/python .venv/bin/python -m pytest tests/python; without
PYTHONPATH the package installed in .venv is tested."""

import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import settings

import peg3d

# No example database in the source tree: every run draws afresh from its seed.
settings.register_profile("peg3d", database=None, derandomize=True)
settings.load_profile("peg3d")

# The programs of the build (peg-collide, peg-matchup) that the parity tests compare with: build/bin, or
# $PEG3D_BIN_DIR; the same whether the package comes from build/python or is installed.
BIN = Path(os.environ.get("PEG3D_BIN_DIR") or Path(__file__).resolve().parents[2] / "build" / "bin")

# Short episodes keep the suite quick; the paper map is the shipped one.
SHORT = {"time_limit": 3.0}


@pytest.fixture
def env():
    e = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=SHORT)
    yield e
    e.close()


def random_actions(env, rng):
    return {a: rng.uniform(-1, 1, 2) * env.action_space(a).high for a in env.agents}


def play(env, seed, actions_seed=0, steps=None):
    """Observations and rewards of one episode under seeded random actions."""
    rng = np.random.default_rng(actions_seed)
    obs, _ = env.reset(seed=seed)
    record = [{k: v.copy() for k, v in obs.items()}]
    n = 0
    while env.agents and (steps is None or n < steps):
        obs, rew, term, trunc, info = env.step(random_actions(env, rng))
        record.append(({k: v.copy() for k, v in obs.items()}, rew, term, trunc))
        n += 1
    return record
