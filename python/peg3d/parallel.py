"""peg3d.parallel_env: one game as a PettingZoo ParallelEnv; peg3d.env: the same game as an AEC env."""

import os

import numpy as np
from gymnasium.spaces import Box
from pettingzoo import ParallelEnv as _ParallelEnv
from pettingzoo.utils.conversions import parallel_to_aec

from . import _loading

REWARD_TERMS = ("obstacle", "target", "success")
RENDER_MODES = ("human", "html", "rgb_array")


class ParallelEnv(_loading.Rebuilt, _loading.Closable, _ParallelEnv):
    """One peg3d game. Agents are pursuer_0.., evader_0.. (those not left to `opponents`); each step() takes an
    action per agent still in the game and returns dicts keyed by the agents that acted."""

    metadata = {"name": "peg3d_v0", "render_modes": list(RENDER_MODES), "is_parallelizable": True, "render_fps": 10}

    def __init__(self, map="maps/paper.yaml", config="peg3d", scenario=None, set=None, opponents=None,
                 render_mode=None, neighbours=2, cache=True, render_path="peg3d_replay.html", max_cycles=None):
        self._made_with = self.remember(locals())
        if render_mode is not None and render_mode not in RENDER_MODES:
            raise ValueError(f"render_mode: None, 'human', 'html' or 'rgb_array', not {render_mode!r}")
        if not isinstance(render_path, (str, os.PathLike)):
            raise TypeError("render_path: a file name")
        if max_cycles is not None and (isinstance(max_cycles, bool) or not isinstance(max_cycles, (int, np.integer))
                                       or max_cycles < 1):
            raise ValueError(f"max_cycles: None or a positive integer, not {max_cycles!r}")
        self.render_mode = render_mode
        self.render_path = str(render_path)
        self.max_cycles = None if max_cycles is None else int(max_cycles)
        self._batch = _loading.make_batch(map, config, scenario, set, opponents, 1, 1, 0, neighbours, cache,
                                          record=render_mode in ("human", "html"))
        self._frames = _loading.frame_renderer(self._batch) if render_mode == "rgb_array" else None
        self._seed = None
        b = self._batch
        # The scenarios the episodes start from, in turn: those named (a name twice plays twice as often), or the
        # map's scenarios with its first one's teams (name one of the others to play it).
        self.scenarios = list(b.scenario_names)
        self.metadata = {**self.metadata, "render_fps": 1.0 / b.dt}  # one frame a step
        names = b.agent_names
        self._index = {n: i for i, n in enumerate(names) if not b.controlled(i)}
        self.possible_agents = list(self._index)
        if not self.possible_agents:
            raise ValueError("opponents: every agent is left to the C++ side; none is left to act")
        spaces = {n: _loading.agent_spaces(b, i) for n, i in self._index.items()}
        self.observation_spaces = {n: spaces[n][0] for n in self._index}
        self.action_spaces = {n: spaces[n][1] for n in self._index}
        self._sizes = {n: spaces[n][0].shape[0] for n in self._index}
        low, high = b.state_bounds()
        self.state_space = Box(low, high, dtype=np.float32)
        # Each agent's observation as the C++ library lays it out (docs/python.md, "Observations"): its segments
        # (name, offset, size, unit, bounds, meaning, shape), in order. An agent's segment is
        # obs[agent][segment.slice]; observation_view(name) shows one segment of every agent that has it in place.
        self.observation_segments = {n: _loading.segments_of(b, i) for n, i in self._index.items()}
        # Kept for older code, read from the segments: the lidar's readings ("lidar.ranges": `rays` entries from
        # `ranges_offset`) and the sight entries ("sight.visible" at `sight_offset`, "sight.age" after it); -1 and 0
        # when no agent has them.
        segs = list(self.observation_segments.values())
        self.rays = _loading.largest_size(segs, "lidar.ranges")
        self.ranges_offset = _loading.compat_offset(segs, "lidar.ranges")
        self.sight_offset = _loading.compat_offset(segs, "sight.visible")
        self.agents = []
        self._cycles = 0
        self._started = False
        self._closed = False

    def save_map(self, agent, path):
        """Writes `agent`'s own map (map.enabled, docs/sensing.md) as it is now, as an OctoMap .bt file."""
        self._check_open()
        if agent not in self._index:
            raise ValueError(f"{agent}: not an agent of this environment")
        self._batch.write_map(0, self._index[agent], os.fspath(path))

    def observation_space(self, agent):
        return self.observation_spaces[agent]

    def observation_view(self, name):
        """Segment `name` (observation_segments) of every agent that has it, in place: a read-only array of shape
        (agents that have it, *the segment's shape), the C++ buffer that the next step overwrites (a depth camera's
        "camera.depth" is (agents, H, W)). Those agents must be consecutive and lay it out alike."""
        self._check_open()
        return _loading.segment_view(self._batch, self._by_index(), name)[0][0]

    def observation_view_space(self, name):
        """A gymnasium Box of observation_view(name): each agent's bounds of the segment."""
        return _loading.segment_view(self._batch, self._by_index(), name)[1]

    def _by_index(self):
        return [(self._index[n], segs) for n, segs in self.observation_segments.items()]

    def action_space(self, agent):
        return self.action_spaces[agent]

    @property
    def num_agents(self):
        return len(self.agents)

    @property
    def max_num_agents(self):
        return len(self.possible_agents)

    def reset(self, seed=None, options=None):
        self._check_open()
        seed = _loading.check_seed(seed)
        self._batch.reset(seed)
        if seed is not None:
            self._seed = seed
        self._cycles = 0
        self._started = True
        active = self._batch.active[0]
        self.agents = [n for n in self.possible_agents if active[self._index[n]]]
        obs = self._batch.observations[0]
        observations = {n: obs[self._index[n], :self._sizes[n]].copy() for n in self.agents}
        infos = {n: {} for n in self.agents}
        return observations, infos

    def step(self, actions):
        self._check_open()
        if not self._started:
            raise RuntimeError("peg3d: step() before reset()")
        if not self.agents:
            raise RuntimeError("peg3d: step() after the episode ended; call reset()")
        if not isinstance(actions, dict):
            raise ValueError("actions: a dict of agent names to actions")
        for n in actions:
            if n not in self._index:
                raise ValueError(f"{n}: not an agent of this environment")
            if n not in self.agents:
                raise ValueError(f"{n}: has left the game and takes no action")
        b = self._batch
        full = np.zeros((1, b.agents, 2))
        for n in self.agents:
            if n not in actions:
                raise ValueError(f"{n}: no action given")
            full[0, self._index[n]] = _loading.check_action(n, actions[n], (2,))
        b.step(full)
        acted = self.agents
        obs, rew, term, trunc = b.observations[0], b.rewards[0], b.terminated[0], b.truncated[0]
        terms, collided, captured = b.reward_terms[0], b.collided[0], b.captured[0]
        observations, rewards, terminations, truncations, infos = {}, {}, {}, {}, {}
        game = b.game_info(0)
        for n in acted:
            i = self._index[n]
            observations[n] = obs[i, :self._sizes[n]].copy()
            rewards[n] = float(rew[i])
            terminations[n] = bool(term[i])
            truncations[n] = bool(trunc[i])
            infos[n] = {"reward_terms": dict(zip(REWARD_TERMS, (float(x) for x in terms[i]))),
                        "collided": bool(collided[i]), "captured": bool(captured[i])}
            if game["done"]:
                infos[n]["outcome"] = game["outcome"]
        self._cycles += 1
        if self.max_cycles is not None and self._cycles >= self.max_cycles and not game["done"]:
            # The episode ends here for Python; the C++ game is left as it is until reset().
            for n in acted:
                truncations[n] = not terminations[n]
                infos[n]["outcome"] = "max_cycles"
        self.agents = [n for n in acted if not (terminations[n] or truncations[n])]
        return observations, rewards, terminations, truncations, infos

    def state(self):
        self._check_open()
        return self._batch.global_state(0)

    def render(self):
        """With render_mode="rgb_array": the game as it stands, seen from a fixed camera above the arena, as a
        (480, 640, 3) uint8 array. With "html": writes the browser replay (docs/viewer.md) of the episode so far
        (the whole episode once it has ended, until the next reset) to render_path and returns that path; with
        "human" the same, returning None: peg3d has no window, the replay is for a human to open in a browser.
        None without a render_mode."""
        self._check_open()
        if self.render_mode is None:
            return None
        if not self._started:
            raise RuntimeError("peg3d: render() before reset()")
        b = self._batch
        if self._frames is not None:
            return self._frames.render(b, 0)
        game = b.game_info(0)
        title = f"{b.map_name}: {', '.join(self.possible_agents)} (episode {b.episode(0)}, seed {self._seed})"
        ending = game["outcome"] if game["done"] else "in progress"
        subtitle = f"peg3d.parallel_env, step {game['step']}, t = {game['time']:.1f} s; {ending}"
        b.write_replay(self.render_path, str(_loading.data_dir() / "assets" / "viewer"), title, subtitle)
        return self.render_path if self.render_mode == "html" else None

    def close(self):
        self._closed = True
        self.agents = []


def aec_env(**kwargs):
    """The game of parallel_env(**kwargs) as a PettingZoo AEC env (agents act in turn; the step is taken once
    all have acted)."""
    return parallel_to_aec(ParallelEnv(**kwargs))
