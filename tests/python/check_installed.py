#!/usr/bin/env python3
"""The package pip installed (tools/python_env.sh --package, which tools/build.sh runs): run from a folder outside
the source tree with no PYTHONPATH, it imports from site-packages, finds its own maps and assets, and plays."""

import importlib.metadata
import sys
from pathlib import Path

import numpy as np
import pettingzoo

import peg3d

where = Path(peg3d._core.__file__).resolve()
assert "site-packages" in where.parts, f"peg3d's module imported from {where}, not from the installed package"
assert importlib.metadata.version("peg3d") == "0.1.0"
data = peg3d._loading.data_dir()
assert data == where.parent / "data" and (data / "maps" / "canyon.yaml").is_file(), data
assert (data / "assets" / "viewer" / "three.min.js").is_file()
env = peg3d.parallel_env(map="maps/canyon.yaml", opponents={"evader": "hide"})
assert isinstance(env, pettingzoo.ParallelEnv)
obs, _ = env.reset(seed=1)
for _ in range(5):
    obs, *_ = env.step({a: np.zeros(2, dtype=np.float32) for a in env.agents})
assert env.observation_space("pursuer_0").contains(obs["pursuer_0"])
print(f"peg3d {importlib.metadata.version('peg3d')} from {where.parent}, maps in {data}", file=sys.stderr)
