"""Bad input raises peg3d.InputError (a ValueError) with the C++ message; bad actions raise ValueError naming
the agent and step nothing (an action that is not finite: the C++ step's own CommandError, a peg3d.InputError)."""

import numpy as np
import pytest

import peg3d
from conftest import SHORT


def test_input_errors_carry_the_message_with_file_and_field(tmp_path):
    with pytest.raises(peg3d.InputError, match="nowhere.yaml"):
        peg3d.parallel_env(map="nowhere.yaml")
    broken = tmp_path / "broken.yaml"
    broken.write_text("name: x\nbounds: [0, 0, 0, 35, 35]\n")
    with pytest.raises(peg3d.InputError, match="broken.yaml") as e:
        peg3d.parallel_env(map=str(broken))
    assert isinstance(e.value, ValueError)
    with pytest.raises(peg3d.InputError, match="pursuer.speed"):
        peg3d.parallel_env(set={"pursuer.speed": -1})
    with pytest.raises(peg3d.InputError, match="no_such_field"):
        peg3d.parallel_env(set={"no_such_field": 1})
    with pytest.raises(peg3d.InputError, match="opponents.evader_0"):
        peg3d.parallel_env(opponents={"evader_0": "no-such-policy"})
    with pytest.raises(peg3d.InputError, match="opponents.evader_7"):
        peg3d.parallel_env(opponents={"evader_7": "flee"})
    with pytest.raises(peg3d.InputError, match="scenario"):
        peg3d.parallel_env(scenario="no-such-scenario")
    with pytest.raises(peg3d.InputError, match="games"):
        peg3d.vector_env(num_envs=0)
    with pytest.raises(peg3d.InputError):
        peg3d.parallel_env(config="no-such-preset")


@pytest.mark.parametrize("bad, message", [
    (np.zeros(3), "pursuer_0: the action's shape"),
    (np.zeros((1, 2)), "pursuer_0: the action's shape"),
    (np.zeros(2, dtype=np.int64), "pursuer_0: the action's dtype"),
    ("left", "pursuer_0: the action's dtype"),
    # Not finite: the C++ step's own check (game::CommandError), not a copy of it here.
    (np.array([np.nan, 0.0]), "game 0: step 1: agent 0 (pursuer 0): steering command (nan, 0) rad is not finite"),
    (np.array([0.0, np.inf]), "game 0: step 1: agent 0 (pursuer 0): steering command (0, inf) rad is not finite"),
])
def test_a_bad_action_names_the_agent_and_steps_nothing(env, bad, message):
    env.reset(seed=0)
    before = env._batch.game_info(0)["step"]
    with pytest.raises(ValueError) as e:
        env.step({"pursuer_0": bad})
    assert message in str(e.value)
    assert env._batch.game_info(0)["step"] == before
    # The same step with a good action goes on as if the bad one had never come.
    env.step({"pursuer_0": np.zeros(2)})
    assert env._batch.game_info(0)["step"] == before + 1


def test_unknown_and_missing_agents_are_refused(env):
    env.reset(seed=0)
    with pytest.raises(ValueError, match="evader_0"):  # played on the C++ side
        env.step({"pursuer_0": np.zeros(2), "evader_0": np.zeros(2)})
    with pytest.raises(ValueError, match="pursuer_0: no action"):
        env.step({})
    with pytest.raises(ValueError):
        env.step([0.0, 0.0])


def test_order_errors_are_clear():
    env = peg3d.parallel_env(opponents={"evader": "flee"}, set=SHORT)
    with pytest.raises(RuntimeError, match="before reset"):
        env.step({"pursuer_0": np.zeros(2)})
    env.close()
    with pytest.raises(RuntimeError, match="closed"):
        env.reset()


def test_vector_actions_are_checked_per_role():
    v = peg3d.vector_env(num_envs=3, threads=2, opponents={"evader": "flee"}, set=SHORT)
    v.reset(seed=0)
    with pytest.raises(ValueError, match="pursuer"):
        v.step({"pursuer": np.zeros((2, 1, 2))})
    bad = np.zeros((3, 1, 2))
    bad[1, 0, 0] = np.nan
    before = [v._batch.game_info(g)["step"] for g in range(3)]
    with pytest.raises(peg3d.InputError, match=r"game 1: step 1: agent 0 \(pursuer 0\): .* not finite"):
        v.step({"pursuer": bad})
    assert [v._batch.game_info(g)["step"] for g in range(3)] == before  # no game of the batch stepped
    with pytest.raises(ValueError, match="referee"):
        v.step({"referee": np.zeros((3, 1, 2))})


def test_the_learner_envs_refuse_steps_after_close_and_before_reset():
    learner = peg3d.LearnerEnv(map="maps/paper.yaml", set=SHORT)
    learner.reset(seed=1)
    learner.close()
    with pytest.raises(RuntimeError, match="closed"):
        learner.step(np.zeros(2, dtype=np.float32))
    with pytest.raises(RuntimeError, match="closed"):
        learner.reset(seed=1)
    many = peg3d.LearnerVectorEnv(num_envs=2, map="maps/paper.yaml", set=SHORT)
    with pytest.raises(RuntimeError, match="before reset"):
        many.step(np.zeros((2, 2), dtype=np.float32))
    many.reset(seed=3)
    many.step(np.zeros((2, 2), dtype=np.float32))
    many.close()
    with pytest.raises(RuntimeError, match="closed"):
        many.step(np.zeros((2, 2), dtype=np.float32))


@pytest.mark.parametrize("bad, at", [(4.9, 1), ("1", 1), (True, 0), (float("nan"), 2), (-1, 0), (2**64, 1),
                                     (np.float64(3.0), 2)])
def test_a_list_of_seeds_refuses_what_a_single_seed_refuses_naming_its_place(bad, at):
    many = peg3d.LearnerVectorEnv(num_envs=3, map="maps/paper.yaml", set=SHORT)
    seeds = [1, 2, 3]
    seeds[at] = bad
    with pytest.raises(ValueError, match=rf"seed\[{at}\]: None or an integer"):
        many.reset(seed=seeds)
    with pytest.raises(ValueError, match="seed: None or an integer"):
        many.reset(seed=bad)
    many.reset(seed=[1, None, np.int64(7)])  # integers of numpy and None (not re-seeded) are seeds


def test_a_batch_over_its_memory_budget_is_refused_before_its_games_are_made():
    fine_maps = dict(SHORT, **{"pursuer.lidar.azimuth_rays": 8, "pursuer.lidar.elevation_rays": 1,
                               "pursuer.map.enabled": True, "pursuer.map.resolution": 0.08})
    # 2048 games with 0.08 m maps of the paper's arena (it once allocated on). A map is budgeted at the bricks an
    # episode's scans can reach: 32 scans (3 s at 10 Hz, and the resets') of 8 rays, each crossing at most 100
    # bricks of 0.32 m, 329 bytes a brick (8.4 MB), the blocks of all 1568 chunks (3.2 MB) and a byte per brick
    # (0.8 MB): about 12.5 MB a game, 26 GB in all (dense, they were 220 MB each)
    with pytest.raises(peg3d.MemoryBudgetError, match=r"2048 games of about 12\.\d MB each .* 12\.5 MB for its "
                                                      r"agents' own maps\) would take about 25\d{3}\.\d MB, more than "
                                                      r"the memory budget of 1000\.0 MB") as refused:
        peg3d.vector_env(num_envs=2048, set=fine_maps, memory_budget=10**9)
    assert isinstance(refused.value, MemoryError)
    with pytest.raises(MemoryError, match="65536 games"):
        peg3d.LearnerVectorEnv(num_envs=65536, map="maps/paper.yaml", memory_budget=10**9)
    peg3d.vector_env(num_envs=64, memory_budget=10**9).reset(seed=1)  # 64 of about 0.2 MB fit
    for bad in (0, -5, 2.5e9, True, "1GB"):
        with pytest.raises(ValueError, match="memory_budget"):
            peg3d.vector_env(num_envs=2, memory_budget=bad)
