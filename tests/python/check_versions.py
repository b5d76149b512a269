#!/usr/bin/env python3
"""The installed package under the versions of numpy, gymnasium and pettingzoo it is run with (tools/test.sh
--python-versions: the oldest pyproject.toml accepts): it imports, passes PettingZoo's parallel API test and
Gymnasium's env checker, and its spaces' bounds are the C++ library's, entry by entry (under NumPy 2 with a
pybind11 older than 2.12 every bound read as the first one)."""

import sys

import gymnasium
import numpy as np
import pettingzoo
from gymnasium.utils.env_checker import check_env
from pettingzoo.test import parallel_api_test

import peg3d

env = peg3d.parallel_env(map="maps/paper.yaml", set={"time_limit": 5.0})
space = env.observation_space("pursuer_0")
names = [name for name, _unit, _meaning in peg3d.OBSERVATION_ENTRIES]
low, high = dict(zip(names, space.low)), dict(zip(names, space.high))
assert low["target_azimuth_error"] < -3.14 and high["target_azimuth_error"] > 3.14, (low, high)
assert low["x"] <= 0 and high["x"] >= 35 and high["target_distance"] > high["target_azimuth_error"], (low, high)
assert len(set(space.high.tolist())) > 3 and len(set(env.state_space.high.tolist())) > 3, "bounds all alike"
parallel_api_test(peg3d.parallel_env(map="maps/paper.yaml", set={"time_limit": 5.0}), num_cycles=100)
check_env(gymnasium.make("peg3d/Pursuer-v0", map="maps/paper.yaml", set={"time_limit": 5.0}).unwrapped)
print(f"peg3d under numpy {np.__version__}, gymnasium {gymnasium.__version__}, pettingzoo {pettingzoo.__version__}: "
      "imported, parallel_api_test and check_env passed, bounds entry by entry", file=sys.stderr)
