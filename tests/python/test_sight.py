"""Limited sight in the observations (docs/sight.md, docs/python.md): the two sight entries sit at
`sight_offset`, within their bounds; an opponent out of sight is given where it was last seen, with the
sighting's age, while `state()` stays the truth; on an open arena with sight all round the observations equal
full information's but for the sight entries."""

import numpy as np

import peg3d
from conftest import SHORT

SIGHT = {"pursuer.sight.enabled": True, "evader.sight.enabled": True}


def test_sight_entries_sit_at_their_offset_within_bounds_and_state_stays_the_truth():
    env = peg3d.parallel_env(map="maps/forest.yaml", opponents={"evader": "hide"},
                             set=dict(SHORT, **SIGHT, **{"pursuer.sight.fov": 90}))
    obs, _ = env.reset(seed=2)
    k = env.sight_offset
    assert k == 20 + 2 * 2 * 4
    space = env.observation_space("pursuer_0")
    hidden = 0
    rng = np.random.default_rng(1)
    for _ in range(150):
        o = obs["pursuer_0"]
        assert space.contains(o)
        assert o[k] in (0.0, 1.0) and o[k + 1] >= 0.0
        state = env.state()
        evader = state[6:9]  # the evader's true position (agent 1's block of six)
        estimate = o[6:9] + o[11:14]  # own position plus the opponent's offset
        if o[k] == 1.0:
            assert o[k + 1] == 0.0
            np.testing.assert_allclose(estimate, evader, atol=1e-4)
        else:
            hidden += 1
        obs, _, term, trunc, _ = env.step({"pursuer_0": rng.uniform(-0.2, 0.2, 2).astype(np.float32)})
        if not env.agents:
            break
    assert hidden > 0  # a 90 degree cone turning at random loses the evader


def test_without_limited_sight_there_are_no_sight_entries():
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=SHORT)
    env.reset(seed=2)
    assert env.sight_offset == -1
    assert env.observation_space("pursuer_0").shape == (20 + 2 * 2 * 4,)


def test_on_an_open_arena_sight_all_round_observes_as_full_information():
    envs = [peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=dict(SHORT, **s))
            for s in ({}, SIGHT)]
    obs = [e.reset(seed=5)[0]["pursuer_0"] for e in envs]
    for _ in range(100):
        k = envs[1].sight_offset
        np.testing.assert_array_equal(obs[0], np.delete(obs[1], [k, k + 1]))
        assert obs[1][k] == 1.0 and obs[1][k + 1] == 0.0
        action = {"pursuer_0": np.array([0.05, -0.02], np.float32)}
        obs = [e.step(action)[0].get("pursuer_0", obs[0]) for e in envs]
        if not envs[0].agents:
            break
