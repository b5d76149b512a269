"""Lidar readings in the observations (docs/python.md, "Observations"): views of the C++ buffer, the readings
where batch.hpp puts them, zeros after a role's own rays, and own-map obstacle entries."""

import numpy as np

import peg3d
from conftest import SHORT


def lidar(role, azimuth, elevation, fov=60, extra=None):
    s = {f"{role}.lidar.azimuth_rays": azimuth, f"{role}.lidar.elevation_rays": elevation,
         f"{role}.lidar.elevation_fov": fov}
    s.update(extra or {})
    return s


def make(sets, num_envs=4, threads=2, map="maps/forest.yaml"):
    return peg3d.vector_env(map=map, num_envs=num_envs, threads=threads, seed=3,
                            set=dict(SHORT, initial_heading="random", **sets))


def test_ranges_are_the_last_entries_of_each_observation_in_the_same_memory():
    v = make({**lidar("pursuer", 16, 4), **lidar("evader", 8, 1)})
    obs, info = v.reset(seed=1)
    assert v.rays == 64 and v.ranges_offset == 36
    assert obs["pursuer"].shape == (4, 1, 100) and v.ranges["pursuer"].shape == (4, 1, 64)
    assert info["ranges"] is v.ranges
    rng = np.random.default_rng(0)
    seen = 0
    for _ in range(20):
        for r in ("pursuer", "evader"):
            ranges = v.ranges[r]
            assert np.shares_memory(ranges, obs[r]) and not ranges.flags.writeable
            np.testing.assert_array_equal(ranges, obs[r][..., 36:])
            assert v.observation_space[r].contains(np.asarray(obs[r]))
        p, e = v.ranges["pursuer"], v.ranges["evader"]
        assert p.min() >= 0 and p.max() <= 10 and e[..., :8].min() >= 0
        assert (e[..., 8:] == 0).all()  # the evader's 8 rays, then zeros
        seen += int((p < 10).sum())
        actions = {r: rng.uniform(-1, 1, (4,) + v.single_action_space[r].shape) * v.single_action_space[r].high
                   for r in ("pursuer", "evader")}
        obs2, *_ = v.step(actions)
        assert obs2["pursuer"] is obs["pursuer"]
    assert seen > 0  # the forest's trees and the arena's faces echo


def test_the_parallel_env_observation_carries_the_ranges():
    env = peg3d.parallel_env(map="maps/forest.yaml", opponents={"evader": "flee"},
                             set=dict(SHORT, **lidar("pursuer", 16, 2)))
    obs, _ = env.reset(seed=4)
    assert env.rays == 32 and env.ranges_offset == 36
    assert obs["pursuer_0"].shape == (68,)
    assert env.observation_space("pursuer_0").contains(obs["pursuer_0"])
    r = obs["pursuer_0"][36:]
    assert r.min() >= 0 and r.max() <= 10
    env.close()


def test_no_lidar_adds_no_entry():
    v = make({})
    obs, info = v.reset(seed=1)
    assert v.rays == 0 and obs["pursuer"].shape == (4, 1, 36) and v.ranges["pursuer"].shape == (4, 1, 0)


def test_own_map_entries_come_from_what_the_agent_has_seen():
    # Without the guard the agents fly the same actions to the same places whatever they sense.
    own = {"pursuer.map.enabled": True, "pursuer.observation.obstacles": "own-map", "pursuer.guard.enabled": False}
    world = make(lidar("pursuer", 16, 4, extra={"pursuer.guard.enabled": False}))
    mapped = make(lidar("pursuer", 16, 4, extra=own))
    # A lidar that reads 0.1 m sees nothing: the agent's map has no occupied cell, its entry 17-19 is 0.
    blind = make(lidar("pursuer", 16, 4, extra={**own, "pursuer.lidar.range": 0.1}))
    ow, om, ob = world.reset(seed=2)[0]["pursuer"], mapped.reset(seed=2)[0]["pursuer"], blind.reset(seed=2)[0]["pursuer"]
    assert (ow[..., 17:20] != 0).any() and (ob[..., 17:20] == 0).all()
    # Entry 3 merges the arena's faces as configured; the obstacles it saw make it nearer than the blind one's.
    assert (ob[..., 3] >= ow[..., 3]).all() and (ob[..., 3] > ow[..., 3]).any()
    # What an agent has sensed is never nearer than the world's nearest obstacle, but for the diagonal of a 0.25 m
    # cell (its distance is to the cube of the cell an echo fell in); and it does sense something.
    diagonal = 0.25 * np.sqrt(3)
    rng = np.random.default_rng(1)
    sensed = 0
    for _ in range(30):
        np.testing.assert_array_equal(om[..., 6:9], ow[..., 6:9])  # the same places
        assert (om[..., 3] >= ow[..., 3] - diagonal - 1e-4).all()
        sensed += int((om[..., 17:20] != 0).any(axis=-1).sum())
        a = {r: rng.uniform(-1, 1, (4,) + world.single_action_space[r].shape) * world.single_action_space[r].high
             for r in ("pursuer", "evader")}
        for e in (world, mapped, blind):
            e.step(a)
    assert sensed > 0


def test_save_map_writes_the_agents_map_as_an_octomap_file(tmp_path):
    env = peg3d.parallel_env(map="maps/forest.yaml", opponents={"evader": "flee"},
                             set=dict(SHORT, **lidar("pursuer", 16, 2, extra={"pursuer.map.enabled": True})))
    env.reset(seed=4)
    rng = np.random.default_rng(2)
    for _ in range(5):
        env.step({a: rng.uniform(-1, 1, 2) * env.action_space(a).high for a in env.agents})
    env.save_map("pursuer_0", tmp_path / "p.bt")
    data = (tmp_path / "p.bt").read_bytes()
    assert data.startswith(b"# Octomap OcTree binary file") and b"res 0.25" in data and len(data) > 200
    env.close()
    # An agent without a map has none to save.
    plain = peg3d.parallel_env(map="maps/forest.yaml", opponents={"evader": "flee"}, set=SHORT)
    plain.reset(seed=4)
    try:
        plain.save_map("pursuer_0", tmp_path / "q.bt")
        raise AssertionError("saved a map the agent does not have")
    except ValueError as e:
        assert "has no map" in str(e)
    assert not (tmp_path / "q.bt").exists()
