"""peg3d/Pursuer-v0 and peg3d/Evader-v0: gymnasium.make gives a gymnasium.Env that check_env accepts on every
shipped map, gymnasium.make_vec gives the C++ batch as a gymnasium.vector.VectorEnv that Gymnasium's vector
wrappers take, and reset() takes a list of seeds and options["reset_mask"]."""

import glob
import os
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from gymnasium.wrappers import vector as vw

import peg3d
from peg3d import _loading

MAPS = sorted(os.path.relpath(p, _loading.data_dir()) for p in glob.glob(str(_loading.data_dir() / "maps" / "*.yaml")))
SHORT = {"time_limit": 3.0}


@pytest.mark.parametrize("env_id", ["peg3d/Pursuer-v0", "peg3d/Evader-v0"])
@pytest.mark.parametrize("map", MAPS, ids=[os.path.basename(m) for m in MAPS])
def test_check_env_accepts_every_map(env_id, map):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # building one warns of nothing
        env = gym.make(env_id, map=map)
    check_env(env.unwrapped, skip_render_check=True)
    assert isinstance(env.unwrapped, peg3d.LearnerEnv)


def test_the_learner_plays_against_cpp_players_and_leaves_at_its_end():
    env = gym.make("peg3d/Pursuer-v0", map="maps/pack.yaml", opponent="flee", teammates="pn")
    b = env.unwrapped._batch
    assert [b.controlled(i) for i in range(b.agents)] == [False, True, True, True, True]
    obs, _ = env.reset(seed=3)
    assert obs.shape == env.observation_space.shape and obs.dtype == np.float32
    steps, done = 0, False
    while not done:
        obs, reward, terminated, truncated, info = env.step(np.zeros(2, dtype=np.float32))
        assert isinstance(reward, float) and env.observation_space.contains(obs)
        done, steps = terminated or truncated, steps + 1
    assert steps <= 1000  # the 100 s time limit at the latest
    with pytest.raises(RuntimeError, match="reset"):
        env.unwrapped.step(np.zeros(2))


def make_vec(n, **kw):
    kw.setdefault("set", SHORT)
    return gym.make_vec("peg3d/Pursuer-v0", num_envs=n, vectorization_mode="vector_entry_point",
                        map="maps/paper.yaml", **kw)


def test_make_vec_gives_a_gymnasium_vector_env_with_gymnasium_spaces():
    v = make_vec(6, threads=2)
    assert isinstance(v, gym.vector.VectorEnv) and v.num_envs == 6
    assert isinstance(v.single_observation_space, gym.spaces.Box)
    assert v.observation_space.shape == (6,) + v.single_observation_space.shape
    assert v.action_space.shape == (6, 2) and v.single_action_space.shape == (2,)
    assert v.metadata["autoreset_mode"] == gym.vector.AutoresetMode.NEXT_STEP
    assert gym.spaces.flatdim(v.single_observation_space) == v.single_observation_space.shape[0]
    obs, _ = v.reset(seed=1)
    o, r, t, tr, info = v.step(v.action_space.sample())
    assert isinstance(o, np.ndarray) and o.shape == (6, 36) and o.dtype == np.float32
    assert r.shape == t.shape == tr.shape == (6,) and t.dtype == tr.dtype == np.bool_
    assert v.observation_space.contains(o)
    # np.logical_or on the flags is what a training loop computes
    assert np.logical_or(t, tr).shape == (6,)


@pytest.mark.parametrize("wrap", [
    vw.RecordEpisodeStatistics, vw.NormalizeObservation, vw.NormalizeReward, vw.ClipAction,
    lambda v: vw.RescaleAction(v, np.float32(-1), np.float32(1)), vw.FlattenObservation,
    lambda v: vw.TransformReward(v, lambda r: 0.5 * r),
    lambda v: vw.DtypeObservation(v, np.float64),
], ids=["RecordEpisodeStatistics", "NormalizeObservation", "NormalizeReward", "ClipAction", "RescaleAction",
        "FlattenObservation", "TransformReward", "DtypeObservation"])
def test_gymnasiums_vector_wrappers_take_it(wrap):
    v = wrap(make_vec(4))
    v.reset(seed=2)
    for _ in range(80):  # past the 3 s limit: every game resets once
        obs, reward, term, trunc, info = v.step(v.action_space.sample())
    assert obs.shape[0] == 4 and reward.shape == (4,)


def test_episode_statistics_count_every_game_that_ended():
    v = vw.RecordEpisodeStatistics(make_vec(4))
    v.reset(seed=0)
    ended = 0
    for _ in range(100):
        _, _, term, trunc, info = v.step(np.zeros((4, 2), dtype=np.float32))
        if "episode" in info:
            assert np.array_equal(info["_episode"], term | trunc)
            ended += int(info["_episode"].sum())
    assert ended >= 4  # 3 s of 0.1 s steps: each game's first episode ends within 31 steps


def trajectory(env, actions):
    out = []
    for a in actions:
        obs, reward, term, trunc, _ = env.step(a)
        out.append((obs.copy(), reward, term, trunc))
        if np.all(term) or np.all(trunc):
            break
    return out


def test_a_list_of_seeds_makes_each_game_play_as_the_single_env_of_its_seed():
    seeds = [5, 17, 5, 2**40]
    v = make_vec(4, set=dict(SHORT, initial_heading="random"))
    v.reset(seed=seeds)
    rng = np.random.default_rng(0)
    actions = [rng.uniform(-0.3, 0.3, (4, 2)) for _ in range(25)]
    batched = trajectory(v, actions)
    for g, s in enumerate(seeds):
        single = gym.make("peg3d/Pursuer-v0", map="maps/paper.yaml", set=dict(SHORT, initial_heading="random"))
        first, _ = single.reset(seed=s)
        alone = trajectory(single.unwrapped, [a[g] for a in actions])
        for k, (x, y) in enumerate(zip(batched, alone)):
            np.testing.assert_array_equal(x[0][g], y[0], err_msg=f"game {g}, step {k}")
            assert x[1][g] == pytest.approx(y[1], abs=0) and x[2][g] == y[2] and x[3][g] == y[3]
    assert not np.array_equal(batched[0][0][0], batched[0][0][1])  # seeds 5 and 17 differ


def test_reset_mask_restarts_only_the_games_it_names():
    v = make_vec(4)
    first, _ = v.reset(seed=[1, 2, 3, 4])
    for _ in range(10):
        before, *_ = v.step(np.full((4, 2), 0.05, dtype=np.float32))
    mask = np.array([False, True, False, True])
    after, _ = v.reset(seed=[None, 2, None, 4], options={"reset_mask": mask})
    np.testing.assert_array_equal(after[~mask], before[~mask])  # left as they were
    np.testing.assert_array_equal(after[mask], first[mask])     # re-seeded alike: the same starts
    later, _ = v.reset(options={"reset_mask": np.array([True, False, False, False])})
    np.testing.assert_array_equal(later[1:], after[1:])
    with pytest.raises(ValueError, match="reset_mask"):
        v.reset(options={"reset_mask": np.array([1, 0, 1, 0])})
    with pytest.raises(ValueError, match="seed"):
        v.reset(seed=[1, 2])
    with pytest.raises(ValueError, match="seed"):
        v.reset(seed=3, options={"reset_mask": mask})


def test_an_int_seed_seeds_the_batch_and_reproduces_it():
    a, b = make_vec(3), make_vec(3)
    np.testing.assert_array_equal(a.reset(seed=9)[0], b.reset(seed=9)[0])
    acts = [np.full((3, 2), 0.02 * k, dtype=np.float32) for k in range(20)]
    for x, y in zip(trajectory(a, acts), trajectory(b, acts)):
        np.testing.assert_array_equal(x[0], y[0])
