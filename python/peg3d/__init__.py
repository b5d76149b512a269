"""peg3d from Python (docs/python.md): the 3D pursuit-evasion game of the C++ library.

    parallel_env(map=..., ...)              one game, PettingZoo's ParallelEnv API
    vector_env(map=..., num_envs=N, ...)    N games stepped by one call on C++ threads (Gymnasium VectorEnv)
    InputError                              a bad map, configuration, policy or keyword (a ValueError)
    PRESETS                                 the configuration presets `config` may name
"""

from ._core import PRESETS, InputError
from .parallel import ParallelEnv
from .spaces import Box
from .vector import VectorEnv

OBSERVATION = (
    "target_distance", "target_azimuth_error", "target_elevation_error",
    "obstacle_distance", "obstacle_azimuth_error", "obstacle_elevation_error",
    "x", "y", "z", "alpha", "theta",
    "opponent_dx", "opponent_dy", "opponent_dz",
    "opponent_vx", "opponent_vy", "opponent_vz",
    "obstacle_dx", "obstacle_dy", "obstacle_dz",
)
"""The names of an observation's first 20 entries; then the neighbours (docs/python.md)."""


def parallel_env(map="maps/paper.yaml", config="peg3d", scenario=None, set=None, opponents=None, render_mode=None,
                 **kwargs):
    return ParallelEnv(map=map, config=config, scenario=scenario, set=set, opponents=opponents,
                       render_mode=render_mode, **kwargs)


def vector_env(map="maps/paper.yaml", num_envs=1, threads=1, **kwargs):
    return VectorEnv(map=map, num_envs=num_envs, threads=threads, **kwargs)


__all__ = ["Box", "InputError", "OBSERVATION", "PRESETS", "ParallelEnv", "VectorEnv", "parallel_env", "vector_env"]
