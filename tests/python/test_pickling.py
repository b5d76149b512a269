"""Environments pickle and copy (docs/python.md, "Pickling"): pickle, cloudpickle and copy.deepcopy rebuild an
environment from the arguments it was made with, so that what ships environments to workers works unmodified:
PettingZoo's Stable-Baselines3 tutorial path (SuperSuit's vector wrappers, then SB3's PPO) runs on parallel_env."""

import copy
import pickle

import cloudpickle
import gymnasium
import numpy as np
import pytest

import peg3d
from conftest import SHORT

WAYS = {"pickle": lambda e: pickle.loads(pickle.dumps(e)), "cloudpickle": lambda e: cloudpickle.loads(cloudpickle.dumps(e)),
        "deepcopy": copy.deepcopy}


@pytest.mark.parametrize("way", WAYS)
def test_a_parallel_env_comes_back_as_the_same_game_not_reset(way):
    env = peg3d.parallel_env(map="maps/pack.yaml", scenario="3v2-cross", opponents={"evader": "flee"}, set=SHORT,
                             neighbours=1)
    first, _ = env.reset(seed=4)
    env.step({a: np.full(2, 0.1, dtype=np.float32) for a in env.agents})  # a game in progress stays behind
    other = WAYS[way](env)
    assert type(other) is type(env) and other is not env and other._batch is not env._batch
    assert other.possible_agents == env.possible_agents and other.scenarios == env.scenarios
    assert [s.name for s in other.observation_segments["pursuer_0"]] == \
        [s.name for s in env.observation_segments["pursuer_0"]]
    with pytest.raises(RuntimeError):
        other.step({a: np.zeros(2, dtype=np.float32) for a in env.possible_agents})
    again, _ = other.reset(seed=4)
    assert set(again) == set(first) and all(np.array_equal(again[a], first[a]) for a in first)


@pytest.mark.parametrize("way", WAYS)
def test_the_aec_vector_and_gymnasium_envs_come_back_playing_the_same(way):
    aec = WAYS[way](peg3d.env(map="maps/paper.yaml", set=SHORT))
    aec.reset(seed=1)
    assert aec.agents == ["pursuer_0", "evader_0"]
    vec = peg3d.vector_env(num_envs=2, opponents={"evader": "flee"}, set=SHORT, seed=3)
    vec2 = WAYS[way](vec)
    np.testing.assert_array_equal(vec.reset(seed=5)[0]["pursuer"], vec2.reset(seed=5)[0]["pursuer"])
    made = gymnasium.make("peg3d/Evader-v0", map="maps/paper.yaml", set=SHORT)
    made2 = WAYS[way](made)
    np.testing.assert_array_equal(made.reset(seed=2)[0], made2.reset(seed=2)[0])
    step = made2.step(np.array([0.2, -0.1], dtype=np.float32))
    np.testing.assert_array_equal(made.step(np.array([0.2, -0.1], dtype=np.float32))[0], step[0])
    many = gymnasium.make_vec("peg3d/Pursuer-v0", num_envs=3, vectorization_mode="vector_entry_point",
                              map="maps/paper.yaml", set=SHORT)
    many2 = WAYS[way](many)
    assert many2.num_envs == 3
    np.testing.assert_array_equal(many.reset(seed=[1, 2, 3])[0], many2.reset(seed=[1, 2, 3])[0])


def test_pettingzoos_stable_baselines3_tutorial_path_trains_on_parallel_env(tmp_path, monkeypatch):
    """PettingZoo's SB3 tutorial (tutorials/SB3/waterworld), unmodified but for the environment: pursuers only,
    the evader left to the C++ side."""
    pytest.importorskip("torch")
    supersuit = pytest.importorskip("supersuit")
    from stable_baselines3 import PPO
    from stable_baselines3.ppo import MlpPolicy

    monkeypatch.setenv("SB3_LOGDIR", str(tmp_path))
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set={"time_limit": 10.0})
    env.reset(seed=0)
    env = supersuit.pettingzoo_env_to_vec_env_v1(env)
    env = supersuit.concat_vec_envs_v1(env, 4, num_cpus=2, base_class="stable_baselines3")
    try:
        model = PPO(MlpPolicy, env, verbose=0, learning_rate=1e-3, batch_size=256, n_steps=256)
        model.learn(total_timesteps=3072)
        assert model.num_timesteps >= 3072
        obs = env.reset()
        action, _ = model.predict(obs, deterministic=True)
        assert action.shape == (4, 2) and np.all(np.isfinite(action))
    finally:
        env.close()
