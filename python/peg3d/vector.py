"""peg3d.vector_env: N games stepped by one call on T C++ threads, after Gymnasium's VectorEnv."""

import numpy as np
from gymnasium.spaces import Box, Dict
from gymnasium.vector import AutoresetMode
from gymnasium.vector.utils import batch_space

from . import _loading
from ._roles import ROLES
from .parallel import REWARD_TERMS


class VectorEnv(_loading.Rebuilt, _loading.Closable):
    """num_envs independent games of one map. Observations, rewards and flags come per role as arrays of shape
    (num_envs, agents of the role, ...), read-only views of the C++ buffers that the next step overwrites
    (copy what you keep). Agents left to `opponents` are played on the C++ side: their actions are ignored."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, map="maps/paper.yaml", num_envs=1, threads=1, config="peg3d", scenario=None, set=None,
                 opponents=None, seed=0, neighbours=2, cache=True, memory_budget=None):
        self._made_with = self.remember(locals())
        self._batch = b = _loading.make_batch(map, config, scenario, set, opponents, num_envs, threads, seed,
                                              neighbours, cache, memory_budget=memory_budget)
        self.num_envs = b.games
        self.scenarios = list(b.scenario_names)  # the starts the episodes take in turn (parallel_env's)
        p = b.pursuers
        self._slices = {"pursuer": slice(0, p), "evader": slice(p, b.agents)}
        self.agent_counts = {"pursuer": p, "evader": b.agents - p}
        self.controlled = {r: np.array([b.controlled(i) for i in range(b.agents)][s], dtype=bool)
                           for r, s in self._slices.items()}
        # Each agent's observation as the C++ library lays it out (docs/python.md, "Observations"), by agent name.
        names = b.agent_names
        self.observation_segments = {names[i]: _loading.segments_of(b, i) for i in range(b.agents)}
        # A gymnasium Dict per role: each role's agents as the rows of its Box, as long as the role's longest
        # observation (a shorter one's row ends in zeros, bounds [0, 0]).
        single_obs, single_act = {}, {}
        self._sizes = {}
        for r in ROLES:
            rows = [_loading.agent_spaces(b, i) for i in range(b.agents)[self._slices[r]]]
            size = max(o.shape[0] for o, _ in rows)
            self._sizes[r] = size
            low = np.zeros((len(rows), size), np.float32)
            high = np.zeros((len(rows), size), np.float32)
            for k, (o, _) in enumerate(rows):
                low[k, :o.shape[0]], high[k, :o.shape[0]] = o.low, o.high
            single_obs[r] = Box(low, high, dtype=np.float32)
            act = rows[0][1]
            single_act[r] = Box(np.tile(act.low, (len(rows), 1)), np.tile(act.high, (len(rows), 1)), dtype=np.float32)
        self.single_observation_space, self.single_action_space = Dict(single_obs), Dict(single_act)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        low, high = b.state_bounds()
        self.single_state_space = Box(low, high, dtype=np.float32)  # state(env), states() rows
        self._actions = np.zeros((self.num_envs, b.agents, 2))
        # The C++ buffers never move: their per-role views are made once and returned by every call.
        self._obs = {r: b.observations[:, s, :self._sizes[r]] for r, s in self._slices.items()}
        self._rew, self._term, self._trunc = self._split(b.rewards), self._split(b.terminated), self._split(b.truncated)
        # Kept for older code, read from the segments: each role's agents' latest lidar readings (m), "lidar.ranges"
        # as a flat list, in place (zero entries for a role without a lidar); `rays` and `ranges_offset`, and the
        # sight entries' `sight_offset` ("sight.visible", then "sight.age"); -1 when no agent has them.
        segs = list(self.observation_segments.values())
        self.rays = _loading.largest_size(segs, "lidar.ranges")
        self.ranges_offset = _loading.compat_offset(segs, "lidar.ranges")
        self.sight_offset = _loading.compat_offset(segs, "sight.visible")
        self.ranges = {}
        for r in ROLES:
            try:
                view = self.observation_view("lidar.ranges")[r]
                self.ranges[r] = view.reshape(view.shape[:2] + (-1,))
            except KeyError:
                self.ranges[r] = np.zeros((self.num_envs, self.agent_counts[r], 0), np.float32)
        terms = self._split(b.reward_terms)
        self._info = {"reset": b.reset_flags, "acted": self._split(b.acted), "active": self._split(b.active),
                      "collided": self._split(b.collided), "captured": self._split(b.captured),
                      "ranges": self.ranges,
                      "reward_terms": {r: dict(zip(REWARD_TERMS, np.moveaxis(t, -1, 0))) for r, t in terms.items()}}
        self._closed = False

    def _split(self, a):
        return {r: a[:, s] for r, s in self._slices.items()}

    def _role_segments(self, r):
        names = self._batch.agent_names
        return [(i, self.observation_segments[names[i]]) for i in range(self._batch.agents)[self._slices[r]]]

    def observation_view(self, name):
        """Segment `name` (observation_segments) in place, per role whose agents have it: {role: read-only array of
        shape (num_envs, the role's agents, *the segment's shape)}, the C++ buffer the next step overwrites (a depth
        camera's "camera.depth" is (num_envs, agents, H, W)). KeyError when no agent has it."""
        out = {}
        for r in ROLES:
            if any(s.name == name for _, segs in self._role_segments(r) for s in segs):
                out[r] = _loading.segment_view(self._batch, self._role_segments(r), name)[0]
        if not out:
            raise KeyError(f"{name}: no agent's observation has this segment")
        return out

    def observation_view_space(self, name):
        """{role: gymnasium Box of one game's observation_view(name)[role]} (each agent's bounds)."""
        return {r: _loading.segment_view(self._batch, self._role_segments(r), name)[1]
                for r in ROLES if any(s.name == name for _, segs in self._role_segments(r) for s in segs)}

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

    def members(self):
        """{role: (num_envs, agents of the role) int32}: which member of its mixture (`opponents`) each C++-played
        agent plays in each game's current episode, an index into that mixture's members in the order given; -1
        for the caller's agents. A copy."""
        self._check_open()
        m = self._batch.members()
        return {r: m[:, s].copy() for r, s in self._slices.items()}

    def close(self):
        self._closed = True
