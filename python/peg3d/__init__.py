"""peg3d from Python (docs/python.md): the 3D pursuit-evasion game of the C++ library.

    parallel_env(map=..., ...)              one game, a PettingZoo ParallelEnv
    env(map=..., ...)                       the same game, a PettingZoo AEC env
    vector_env(map=..., num_envs=N, ...)    N games stepped by one call on C++ threads, per role
    gymnasium.make("peg3d/Pursuer-v0")      one learner against C++ players (also Evader-v0), a gymnasium.Env;
    gymnasium.make_vec("peg3d/Pursuer-v0", num_envs=N)   N of them as a gymnasium.vector.VectorEnv
    InputError                              a bad map, configuration, policy or keyword (a ValueError)
    MemoryBudgetError                       games that would take more than memory_budget (a MemoryError)
    PRESETS                                 the configuration presets `config` may name
    PLAYERS                                 the C++ players `opponents` may name: (name, roles, needs, help) each
    save_policy(path, role=, observation=, layers=, ...)   a network as a policy file the C++ side plays
    upgrade_policy(path, env, agent)        a version 1 policy file re-saved with the observation it reads
"""

from ._core import OBSERVATION_ENTRIES, PLAYERS, PRESETS, InputError, MemoryBudgetError
from gymnasium.spaces import Box

from ._loading import Segment
from .learner import LearnerEnv, LearnerVectorEnv, register
from .parallel import ParallelEnv, aec_env
from .policy import MIXTURE_FORMAT, read_policy, save_policy, upgrade_policy
from .vector import VectorEnv

register()

OBSERVATION = tuple(name for name, _unit, _meaning in OBSERVATION_ENTRIES)
"""The names of an observation's first 20 entries, as the C++ library declares them (OBSERVATION_ENTRIES: name,
unit, meaning); then the neighbours (docs/python.md)."""


def parallel_env(map="maps/paper.yaml", config="peg3d", scenario=None, set=None, opponents=None, render_mode=None,
                 **kwargs):
    return ParallelEnv(map=map, config=config, scenario=scenario, set=set, opponents=opponents,
                       render_mode=render_mode, **kwargs)


def env(map="maps/paper.yaml", config="peg3d", scenario=None, set=None, opponents=None, render_mode=None, **kwargs):
    return aec_env(map=map, config=config, scenario=scenario, set=set, opponents=opponents, render_mode=render_mode,
                   **kwargs)


def vector_env(map="maps/paper.yaml", num_envs=1, threads=1, **kwargs):
    return VectorEnv(map=map, num_envs=num_envs, threads=threads, **kwargs)


__all__ = ["Box", "InputError", "LearnerEnv", "MemoryBudgetError", "LearnerVectorEnv", "OBSERVATION", "OBSERVATION_ENTRIES", "PLAYERS", "PRESETS",
           "MIXTURE_FORMAT", "ParallelEnv", "Segment", "VectorEnv", "env", "parallel_env", "read_policy", "save_policy", "upgrade_policy",
           "vector_env"]
