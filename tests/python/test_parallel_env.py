"""peg3d.parallel_env's own behaviour: its agents, spaces and infos, captures, seeds, state, team maps and
max_cycles. PettingZoo's generic checks run in test_pettingzoo.py."""

import numpy as np
import pytest

import peg3d
from conftest import SHORT, play, random_actions


def test_agents_and_spaces_follow_the_parallel_api(env):
    assert env.possible_agents == ["pursuer_0"]
    assert env.agents == []  # before reset
    assert env.observation_space("pursuer_0") is env.observation_space("pursuer_0")
    assert env.action_space("pursuer_0") is env.action_space("pursuer_0")
    obs, infos = env.reset(seed=1)
    assert set(obs) == set(infos) == set(env.agents) <= set(env.possible_agents)
    space = env.observation_space("pursuer_0")
    assert obs["pursuer_0"].dtype == np.float32 and obs["pursuer_0"].shape == space.shape == (36,)
    assert np.all(np.isfinite(space.low)) and np.all(np.isfinite(space.high))
    assert space.contains(obs["pursuer_0"])
    assert len(peg3d.OBSERVATION) == 20


def test_every_step_returns_dicts_of_the_agents_that_acted(env):
    rng = np.random.default_rng(3)
    env.reset(seed=2)
    steps = 0
    while env.agents:
        acting = list(env.agents)
        obs, rew, term, trunc, info = env.step(random_actions(env, rng))
        for d in (obs, rew, term, trunc, info):
            assert set(d) == set(acting)
        for a in acting:
            assert env.observation_space(a).contains(obs[a])
            assert isinstance(rew[a], float) and isinstance(term[a], bool) and isinstance(trunc[a], bool)
            assert set(info[a]["reward_terms"]) == {"obstacle", "target", "success"}
            if term[a] or trunc[a]:
                assert a not in env.agents
        steps += 1
    assert steps <= 30  # 3 s of 0.1 s steps at most
    assert trunc["pursuer_0"] or term["pursuer_0"]
    assert info["pursuer_0"]["outcome"] in ("capture", "timeout", "pursuer collision", "evader collision")
    with pytest.raises(RuntimeError, match="after the episode ended"):
        env.step({})


def test_a_captured_evader_leaves_the_agents():
    # The evader played from Python, nearly standing before a pure-pursuit pursuer: it leaves on its capture.
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"pursuer": "pure-pursuit"},
                             set={"time_limit": 60.0, "evader.speed": 0.05})
    env.reset(seed=1)
    left, last = [], None
    while env.agents:
        before = list(env.agents)
        _, _, term, trunc, info = env.step({a: np.zeros(2) for a in env.agents})
        left += [a for a in before if a not in env.agents]
        last = info
    assert left == ["evader_0"]
    assert last["evader_0"]["outcome"] in ("capture", "timeout")


def test_seeds_reproduce_episodes_exactly():
    a = peg3d.parallel_env(opponents={"evader": "flee"}, set=dict(SHORT, initial_heading="random"))
    b = peg3d.parallel_env(opponents={"evader": "flee"}, set=dict(SHORT, initial_heading="random"))
    first, again = play(a, seed=11), play(b, seed=11)
    assert len(first) == len(again)
    for x, y in zip(first[1:], again[1:]):
        assert x[1] == y[1] and x[2] == y[2] and x[3] == y[3]
        for k in x[0]:
            np.testing.assert_array_equal(x[0][k], y[0][k])
    other = play(a, seed=12)
    assert not np.array_equal(first[0]["pursuer_0"], other[0]["pursuer_0"])  # another random heading
    # The same env reset with the same seed replays it too.
    replay = play(a, seed=11)
    np.testing.assert_array_equal(replay[-1][0].get("pursuer_0", np.zeros(1)), first[-1][0].get("pursuer_0", np.zeros(1)))


def test_state_is_a_global_vector(env):
    env.reset(seed=0)
    s = env.state()
    assert s.shape == env.state_space.shape and s.dtype == np.float32 and env.state_space.contains(s)
    assert s.shape == (2 * 6 + 1,)


def test_a_saved_policy_can_play_the_opponent(tmp_path):
    # A policy file the league ships in its test data, if any, else one written by peg-paper is not needed:
    # an unreadable one is an InputError naming the file.
    bad = tmp_path / "policy.json"
    bad.write_text("{}")
    with pytest.raises(peg3d.InputError, match="policy.json"):
        peg3d.parallel_env(opponents={"evader": str(bad)})


def test_every_preset_the_package_names_builds_a_game():
    assert "peg3d" in peg3d.PRESETS and "robust" in peg3d.PRESETS
    for name in peg3d.PRESETS:
        env = peg3d.parallel_env(config=name, opponents={"evader": "flee"}, set=SHORT)
        observations, _ = env.reset(seed=0)
        assert set(observations) == {"pursuer_0"}
        env.close()


def test_a_team_map_plays_the_first_starts_teams_unless_a_scenario_is_named():
    both = peg3d.parallel_env(map="maps/pack.yaml")
    assert both.scenarios == ["3v2-corners", "3v2-cross"]
    assert both.possible_agents == ["pursuer_0", "pursuer_1", "pursuer_2", "evader_0", "evader_1"]
    duel = peg3d.parallel_env(map="maps/pack.yaml", scenario="2v2-middle")
    assert duel.scenarios == ["2v2-middle"]
    assert duel.possible_agents == ["pursuer_0", "pursuer_1", "evader_0", "evader_1"]


def test_max_cycles_truncates_every_agent_at_that_step_and_each_episode_anew():
    env = peg3d.parallel_env(opponents={"evader": "flee"}, max_cycles=3)
    for seed in (1, 2):
        env.reset(seed=seed)
        for k in range(3):
            assert env.agents == ["pursuer_0"]
            _, _, term, trunc, info = env.step({"pursuer_0": np.zeros(2)})
        assert trunc == {"pursuer_0": True} and term == {"pursuer_0": False}
        assert info["pursuer_0"]["outcome"] == "max_cycles" and env.agents == []
    for bad in (0, -1, 2.5, True):
        with pytest.raises(ValueError, match="max_cycles"):
            peg3d.parallel_env(max_cycles=bad)


def test_the_aec_env_steps_the_game_once_every_agent_has_acted():
    aec = peg3d.env(opponents={"evader": "flee"}, set=SHORT)
    par = peg3d.parallel_env(opponents={"evader": "flee"}, set=SHORT)
    aec.reset(seed=5)
    obs, _ = par.reset(seed=5)
    np.testing.assert_array_equal(aec.observe("pursuer_0"), obs["pursuer_0"])
    action = np.array([0.05, -0.02], dtype=np.float32)
    aec.step(action)
    obs, rew, _, _, _ = par.step({"pursuer_0": action})
    np.testing.assert_array_equal(aec.observe("pursuer_0"), obs["pursuer_0"])
    assert aec.rewards["pursuer_0"] == rew["pursuer_0"]
