"""peg3d.vector_env: N games stepped by one call on T C++ threads, after Gymnasium's VectorEnv."""

import numpy as np
from gymnasium.spaces import Box, Dict
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from . import _loading
from .parallel import REWARD_TERMS

ROLES = ("pursuer", "evader")


class VectorEnv:
    """num_envs independent games of one map. Observations, rewards and flags come per role as arrays of shape
    (num_envs, agents of the role, ...), read-only views of the C++ buffers that the next step overwrites
    (copy what you keep). Agents left to `opponents` are played on the C++ side: their actions are ignored."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, map="maps/paper.yaml", num_envs=1, threads=1, config="peg3d", scenario=None, set=None,
                 opponents=None, seed=0, neighbours=2, cache=True):
        self._batch = b = _loading.make_batch(map, config, scenario, set, opponents, num_envs, threads, seed,
                                              neighbours, cache)
        self.num_envs = b.games
        self.scenarios = list(b.scenario_names)  # the starts the episodes take in turn (parallel_env's)
        p = b.pursuers
        self._slices = {"pursuer": slice(0, p), "evader": slice(p, b.agents)}
        self.agent_counts = {"pursuer": p, "evader": b.agents - p}
        self.controlled = {r: np.array([b.controlled(i) for i in range(b.agents)][s], dtype=bool)
                           for r, s in self._slices.items()}
        # A gymnasium Dict per role: each role's agents as the rows of its Box.
        single_obs, single_act = {}, {}
        for r in ROLES:
            obs, act = _loading.role_spaces(b, r == "pursuer")
            n = self.agent_counts[r]
            single_obs[r] = Box(np.tile(obs.low, (n, 1)), np.tile(obs.high, (n, 1)), dtype=np.float32)
            single_act[r] = Box(np.tile(act.low, (n, 1)), np.tile(act.high, (n, 1)), dtype=np.float32)
        self.single_observation_space, self.single_action_space = Dict(single_obs), Dict(single_act)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        low, high = b.state_bounds()
        self.single_state_space = Box(low, high, dtype=np.float32)  # state(env), states() rows
        self._actions = np.zeros((self.num_envs, b.agents, 2))
        # The C++ buffers never move: their per-role views are made once and returned by every call.
        self._obs = self._split(b.observations)
        self._rew, self._term, self._trunc = self._split(b.rewards), self._split(b.terminated), self._split(b.truncated)
        # Each agent's latest lidar readings (m): the last `rays` entries of its observation, the same memory.
        self.rays, self.ranges_offset = b.rays, b.ranges_offset
        # With limited sight (docs/sight.md): entries sight_offset and sight_offset + 1 say whether the agent sees
        # the opponent of its first entries now (1 or 0) and how old (s) the sighting they come from is; -1: no
        # agent's sight is limited, no such entries.
        self.sight_offset = b.sight_offset
        self.ranges = self._split(b.ranges)
        terms = self._split(b.reward_terms)
        self._info = {"reset": b.reset_flags, "acted": self._split(b.acted), "active": self._split(b.active),
                      "collided": self._split(b.collided), "captured": self._split(b.captured),
                      "ranges": self.ranges,
                      "reward_terms": {r: dict(zip(REWARD_TERMS, np.moveaxis(t, -1, 0))) for r, t in terms.items()}}
        self._closed = False

    def _split(self, a):
        return {r: a[:, s] for r, s in self._slices.items()}

    def _check_open(self):
        if self._closed:
            raise RuntimeError("peg3d: the environment is closed")

    def reset(self, seed=None, options=None):
        self._check_open()
        self._batch.reset(_loading.check_seed(seed))
        return self._obs, self._info

    def step(self, actions):
        self._check_open()
        if not isinstance(actions, dict):
            raise ValueError("actions: a dict of role ('pursuer', 'evader') to an array (num_envs, agents, 2)")
        for r in actions:
            if r not in self._slices:
                raise ValueError(f"{r}: not a role (pursuer, evader)")
        for r, s in self._slices.items():
            n = self.agent_counts[r]
            if r not in actions:
                if not self.controlled[r].all():
                    raise ValueError(f"{r}: no actions given")
                continue
            self._actions[:, s] = _loading.check_action(r, actions[r], (self.num_envs, n, 2))
        self._batch.step(self._actions)
        return self._obs, self._rew, self._term, self._trunc, self._info

    def state(self, env):
        self._check_open()
        return self._batch.global_state(env)

    def states(self):
        """Every game's state() at once: (num_envs, state size) float32, a copy; for centralised critics."""
        self._check_open()
        return self._batch.global_states()

    def close(self):
        self._closed = True
