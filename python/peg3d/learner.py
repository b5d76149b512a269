"""Gymnasium environments with one learning agent, every other agent played on the C++ side: LearnerEnv, a
gymnasium.Env, and LearnerVectorEnv, a gymnasium.vector.VectorEnv of N such games stepped by one call on C++
threads. Registered as peg3d/Pursuer-v0 and peg3d/Evader-v0 (gymnasium.make, gymnasium.make_vec)."""

import gymnasium
import numpy as np
from gymnasium.spaces import Box
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from . import _core, _loading
from ._roles import ROLES, other_role

# What plays the other agents unless told: each role's first baseline player of the C++ registry (flee for the
# evaders, pure-pursuit for the pursuers): the learner's opponents and its teammates.
DEFAULT_PLAYERS = {learner: (_core.BASELINE_PLAYERS[other_role(learner)][0], _core.BASELINE_PLAYERS[learner][0])
                   for learner in ROLES}


def _make(map, learner, opponent, teammates, config, scenario, set, num_envs, threads, seed, neighbours, cache,
          memory_budget=None):
    """The batch, with every agent but the learner (agent 0 of its role) left to the C++ side."""
    if learner not in ROLES:
        raise ValueError(f"learner: 'pursuer' or 'evader', not {learner!r}")
    other = other_role(learner)
    opponent = DEFAULT_PLAYERS[learner][0] if opponent is None else opponent
    teammates = DEFAULT_PLAYERS[learner][1] if teammates is None else teammates
    # Later keys win: the role's players, then the learner itself back to the caller ("").
    players = {other: opponent, learner: teammates}
    batch = _loading.make_batch(map, config, scenario, set, players, num_envs, threads, seed, neighbours, cache,
                                extra_controllers=[(f"{learner}_0", "")], memory_budget=memory_budget)
    agent = 0 if learner == "pursuer" else batch.pursuers
    return batch, agent


def _check_render_mode(mode):
    if mode not in (None, "rgb_array"):
        raise ValueError(f"render_mode: None or 'rgb_array', not {mode!r} (parallel_env also writes replays)")


def _spaces(batch, agent):
    return _loading.agent_spaces(batch, agent)


def _segment_view(env, name, games):
    """The learner's segment `name` in place: (games, *shape) of the batch's observations."""
    seg = _loading.segment_named(env.observation_segments, name)
    return env._batch.segment_view(seg.offset, list(seg.shape), env._agent, 1)[:games, 0]


class LearnerEnv(_loading.Rebuilt, _loading.Closable, gymnasium.Env):
    """One game in which the learner (pursuer_0 or evader_0) takes the actions and C++ plays everyone else.
    Observations, actions and rewards are parallel_env's for that agent (docs/python.md). terminated: the
    learner's game is over for it (capture, collision); truncated: the time limit."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, map="maps/paper.yaml", learner="pursuer", opponent=None, teammates=None, config="peg3d",
                 scenario=None, set=None, neighbours=2, cache=True, render_mode=None):
        self._made_with = self.remember(locals())
        _check_render_mode(render_mode)
        self.render_mode = render_mode
        self._batch, self._agent = _make(map, learner, opponent, teammates, config, scenario, set, 1, 1, 0,
                                         neighbours, cache)
        self.learner = learner
        self.scenarios = list(self._batch.scenario_names)
        self.metadata = {**self.metadata, "render_fps": 1.0 / self._batch.dt}  # one frame a step
        self.observation_space, self.action_space = _spaces(self._batch, self._agent)
        # The learner's observation as the C++ library lays it out (docs/python.md, "Observations").
        self.observation_segments = _loading.segments_of(self._batch, self._agent)
        self._size = self.observation_space.shape[0]
        self._actions = np.zeros((1, self._batch.agents, 2))
        self._done = True
        self._frames = _loading.frame_renderer(self._batch) if render_mode else None

    def render(self):
        """With render_mode="rgb_array": the game as it stands from a fixed camera, (480, 640, 3) uint8."""
        return None if self._frames is None else self._frames.render(self._batch, 0)

    def close(self):
        self._closed = True
        self._done = True

    def reset(self, *, seed=None, options=None):
        self._check_open()
        seed = _loading.check_seed(seed)
        super().reset(seed=seed)
        self._batch.reset(seed)
        self._done = False
        return self._batch.observations[0, self._agent, :self._size].copy(), {}

    def step(self, action):
        self._check_open()
        if self._done:
            raise RuntimeError("peg3d: step() before reset() or after the episode ended; call reset()")
        self._actions[0, self._agent] = _loading.check_action(self.learner, action, (2,))
        b = self._batch
        b.step(self._actions)
        i = self._agent
        terminated, truncated = bool(b.terminated[0, i]), bool(b.truncated[0, i])
        self._done = terminated or truncated
        info = {"collided": bool(b.collided[0, i]), "captured": bool(b.captured[0, i])}
        game = b.game_info(0)
        if game["done"]:
            info["outcome"] = game["outcome"]
        return b.observations[0, i, :self._size].copy(), float(b.rewards[0, i]), terminated, truncated, info

    def observation_view(self, name):
        """The learner's segment `name` (observation_segments) in place, shaped as the segment is (a depth
        camera's "camera.depth" is (H, W)): read-only, overwritten by the next step."""
        return _segment_view(self, name, 1)[0]

    def state(self):
        """The global state of parallel_env.state(): the truth for every agent, for centralised critics."""
        return self._batch.global_state(0)


class LearnerVectorEnv(_loading.Rebuilt, _loading.Closable, VectorEnv):
    """num_envs games of LearnerEnv, stepped by one call on `threads` C++ threads. Arrays of shape (num_envs, ...)
    everywhere; autoreset is next-step (metadata["autoreset_mode"]): the step after a game ended resets it and
    ignores its action. reset(seed=int) seeds the batch (game g's episodes from derive_seed(seed, {g, e}));
    reset(seed=[s0, s1, ...]) seeds each game alone, so that game g plays as LearnerEnv reset with s_g; None in
    the list, or a game left out by options["reset_mask"], is not re-seeded."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, num_envs=1, map="maps/paper.yaml", learner="pursuer", opponent=None, teammates=None,
                 config="peg3d", scenario=None, set=None, threads=1, seed=0, neighbours=2, cache=True,
                 render_mode=None, memory_budget=None):
        self._made_with = self.remember(locals())
        _check_render_mode(render_mode)
        self.render_mode = render_mode
        self._batch, self._agent = _make(map, learner, opponent, teammates, config, scenario, set, num_envs, threads,
                                         seed, neighbours, cache, memory_budget)
        b = self._batch
        self.num_envs = b.games
        self.learner = learner
        self.scenarios = list(b.scenario_names)
        self.metadata = {**self.metadata, "render_fps": 1.0 / b.dt}  # one frame a step
        self.single_observation_space, self.single_action_space = _spaces(b, self._agent)
        # The learner's observation as the C++ library lays it out (docs/python.md, "Observations").
        self.observation_segments = _loading.segments_of(b, self._agent)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._actions = np.zeros((self.num_envs, b.agents, 2))
        i = self._agent
        # Views of the learner's column of the C++ buffers, made once; step() returns copies.
        self._obs, self._rew = b.observations[:, i, :self.single_observation_space.shape[0]], b.rewards[:, i]
        self._term, self._trunc = b.terminated[:, i], b.truncated[:, i]
        self._captured, self._collided, self._reset = b.captured[:, i], b.collided[:, i], b.reset_flags
        self._frames = _loading.frame_renderer(b) if render_mode else None
        self._started = False

    def close_extras(self, **kwargs):
        self._closed = True

    def render(self):
        """With render_mode="rgb_array": every game's image as LearnerEnv.render() gives it, a tuple."""
        if self._frames is None:
            return None
        return tuple(self._frames.render(self._batch, g) for g in range(self.num_envs))

    def reset(self, *, seed=None, options=None):
        self._check_open()
        per_game = isinstance(seed, (list, tuple, np.ndarray))
        if not per_game:
            seed = _loading.check_seed(seed)
        super().reset(seed=None if per_game else seed)
        mask = None if options is None else options.get("reset_mask")
        if mask is not None:
            mask = np.asarray(mask)
            if mask.shape != (self.num_envs,) or mask.dtype != np.bool_:
                raise ValueError(f"options['reset_mask']: a bool array of shape ({self.num_envs},)")
        if per_game:
            if len(seed) != self.num_envs:
                raise ValueError(f"seed: a list of {self.num_envs} seeds (or None), not {len(seed)}")
            seeds = [_loading.check_seed(s, f"seed[{g}]") for g, s in enumerate(seed)]
        b = self._batch
        if mask is None and not per_game:
            b.reset(seed)
        else:
            if seed is not None and not per_game:
                raise ValueError("seed: with options['reset_mask'], None or a list of one seed (or None) per game")
            for g in range(self.num_envs):
                if mask is None or mask[g]:
                    b.reset_game(g, seeds[g] if per_game else None)
        self._started = True
        return self._obs.copy(), {}

    def step(self, actions):
        self._check_open()
        if not self._started:
            raise RuntimeError("peg3d: step() before reset(); call reset()")
        self._actions[:, self._agent] = _loading.check_action(self.learner, actions, (self.num_envs, 2))
        self._batch.step(self._actions)
        info = {"captured": self._captured.astype(bool), "collided": self._collided.astype(bool),
                "reset": self._reset.astype(bool)}
        return (self._obs.copy(), self._rew.astype(np.float64), self._term.astype(bool), self._trunc.astype(bool),
                info)

    def state(self, env):
        """The global state of game `env` (parallel_env.state())."""
        return self._batch.global_state(env)

    def observation_view(self, name):
        """The learner's segment `name` in every game, in place: (num_envs, *the segment's shape)."""
        return _segment_view(self, name, self.num_envs)


def register():
    """peg3d/Pursuer-v0 and peg3d/Evader-v0 for gymnasium.make and gymnasium.make_vec."""
    for name, learner in (("Pursuer", "pursuer"), ("Evader", "evader")):
        env_id = f"peg3d/{name}-v0"
        if env_id in gymnasium.registry:
            continue
        gymnasium.register(id=env_id, entry_point="peg3d.learner:LearnerEnv",
                           vector_entry_point="peg3d.learner:LearnerVectorEnv", kwargs={"learner": learner},
                           disable_env_checker=False)
