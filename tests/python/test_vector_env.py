"""peg3d.vector_env: Gymnasium's VectorEnv contract, next-step autoreset, zero-copy buffers, thread independence."""

import numpy as np
import pytest

import peg3d
from conftest import SHORT


def make(threads=1, num_envs=8, **kw):
    return peg3d.vector_env(map="maps/paper.yaml", num_envs=num_envs, threads=threads,
                            set=dict(SHORT, initial_heading="random"), seed=5, **kw)


def actions_for(v, rng):
    return {r: rng.uniform(-1, 1, (v.num_envs,) + v.single_action_space[r].shape) * v.single_action_space[r].high
            for r in ("pursuer", "evader")}


def test_spaces_and_shapes():
    v = make()
    assert v.num_envs == 8
    assert v.metadata["autoreset_mode"] in ("NextStep",) or str(v.metadata["autoreset_mode"]).endswith("NEXT_STEP")
    obs, info = v.reset(seed=1)
    assert obs["pursuer"].shape == (8, 1, 36) and obs["evader"].shape == (8, 1, 36)
    assert v.observation_space.contains({r: np.asarray(o) for r, o in obs.items()})
    sample = v.action_space.sample()
    assert sample["pursuer"].shape == (8, 1, 2) and v.action_space.contains(sample)
    obs2, rew, term, trunc, info = v.step(sample)
    assert rew["pursuer"].shape == (8, 1) and term["evader"].dtype == bool
    assert set(info) >= {"reset", "acted", "active", "collided", "captured", "reward_terms"}


def test_results_are_views_of_the_cpp_buffers():
    v = make()
    obs, _ = v.reset(seed=1)
    first = obs["pursuer"]
    assert not first.flags.writeable and not first.flags.owndata
    obs2, *_ = v.step(v.action_space.sample())
    assert obs2["pursuer"] is first  # the same view, rewritten in place


def test_next_step_autoreset():
    v = make(num_envs=4)
    rng = np.random.default_rng(0)
    v.reset(seed=2)
    ended = None
    for _ in range(40):  # 3 s episodes of 30 steps
        obs, rew, term, trunc, info = v.step(actions_for(v, rng))
        done = term["pursuer"][:, 0] | trunc["pursuer"][:, 0]
        if done.any():
            ended = np.flatnonzero(done)
            break
    assert ended is not None
    obs, rew, term, trunc, info = v.step(actions_for(v, rng))
    for g in ended:
        assert info["reset"][g]                # this step reset the game and ignored its actions
        assert rew["pursuer"][g, 0] == 0.0 and not term["pursuer"][g, 0] and not trunc["pursuer"][g, 0]
        assert not info["acted"]["pursuer"][g, 0]
    others = [g for g in range(4) if g not in ended]
    assert not info["reset"][others].any()


def run(threads, steps=60):
    v = make(threads=threads, num_envs=7)
    rng = np.random.default_rng(9)
    obs, _ = v.reset(seed=3)
    out = [obs["pursuer"].copy()]
    for _ in range(steps):
        obs, rew, *_ = v.step(actions_for(v, rng))
        out += [obs["pursuer"].copy(), obs["evader"].copy(), rew["pursuer"].copy()]
    return out


def test_results_do_not_depend_on_the_thread_count():
    one, two, three = run(1), run(2), run(3)
    for a, b, c in zip(one, two, three):
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(a, c)


def test_each_game_is_the_parallel_env_game_of_its_seed():
    # Game g of the batch plays what a batch of one plays with the same root seed, in game 0 - only when g = 0;
    # the other games start from their own derived seeds (random headings differ).
    v = make(num_envs=3)
    obs, _ = v.reset(seed=4)
    starts = obs["pursuer"][:, 0, 9]  # alpha
    assert len(set(starts.tolist())) == 3


def assert_game_g_starts_as_scenario_g(v, names):
    """After a reset with seed 0, game g of the paper-map env `v` starts where a one-game env of names[g] starts."""
    v.reset(seed=0)
    for g, name in enumerate(names):
        one = peg3d.vector_env(map="maps/paper.yaml", num_envs=1, threads=1, scenario=name, opponents={"evader": "flee"})
        one.reset(seed=0)
        np.testing.assert_array_equal(v._batch.agent_states(g)[:, :3], one._batch.agent_states(0)[:, :3])
        one.close()
    v.close()


def test_the_games_spread_over_the_maps_scenarios_from_the_first_episode():
    # episode e of game g plays scenario (g + e) mod count: with 4 games on the paper map's 4 starts, game g
    # starts where a game of scenario S(g+1) starts
    v = peg3d.vector_env(map="maps/paper.yaml", num_envs=4, threads=1, opponents={"evader": "flee"})
    assert_game_g_starts_as_scenario_g(v, ["S1", "S2", "S3", "S4"])


def test_a_list_of_scenarios_takes_turns_in_its_order_repeats_and_all():
    # scenario=[S4, S1, S4]: game g starts where a game of the (g mod 3)-th named scenario starts
    names = ["S4", "S1", "S4"]
    v = peg3d.vector_env(map="maps/paper.yaml", num_envs=3, threads=1, scenario=names, opponents={"evader": "flee"})
    assert v.scenarios == names
    assert_game_g_starts_as_scenario_g(v, names)
    with pytest.raises(TypeError, match="scenario"):
        peg3d.vector_env(map="maps/paper.yaml", scenario=["S1", 2])
    with pytest.raises(peg3d.InputError, match="S9"):
        peg3d.vector_env(map="maps/paper.yaml", scenario=["S1", "S9"])


def test_states_are_every_games_state_in_its_space():
    v = peg3d.vector_env(map="maps/pack.yaml", num_envs=3, opponents={"evader": "flee"}, seed=4)
    v.reset(seed=4)
    for _ in range(5):
        v.step({"pursuer": np.zeros((3, 3, 2))})
    states = v.states()
    assert states.shape == (3,) + v.single_state_space.shape and states.dtype == np.float32
    for g in range(3):
        np.testing.assert_array_equal(states[g], v.state(g))
        assert v.single_state_space.contains(states[g])
    assert not np.array_equal(states[0], states[1])  # the two 3 v 2 starts
