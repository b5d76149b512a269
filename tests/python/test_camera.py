"""A depth camera in Python (docs/sensing.md, "Depth camera"): each agent's image as its observation segment
"camera.depth", seen in place as (agents, H, W) float32 per game with its gymnasium Box, on every env."""

import numpy as np
import pytest

import peg3d
from conftest import SHORT

H, W, RANGE = 12, 16, 9.0
CAMERA = {"pursuer.camera.width": W, "pursuer.camera.height": H, "pursuer.camera.range": RANGE,
          "pursuer.camera.hfov": 100}


def test_the_parallel_env_shows_each_pursuers_image_in_place():
    env = peg3d.parallel_env(map="maps/pack.yaml", scenario="3v2-cross", set=dict(SHORT, **CAMERA))
    obs, _ = env.reset(seed=2)
    pursuers = [a for a in env.possible_agents if a.startswith("pursuer")]
    depth = env.observation_view("camera.depth")
    assert depth.shape == (len(pursuers), H, W) and depth.dtype == np.float32 and not depth.flags.writeable
    space = env.observation_view_space("camera.depth")
    assert space.shape == depth.shape and space.dtype == np.float32
    # [0, range] widened by one float step each way (game/observation.hpp)
    assert np.all(space.low == np.nextafter(np.float32(0), np.float32(-1)))
    assert np.all(space.high == np.nextafter(np.float32(RANGE), np.float32(RANGE + 1)))
    for a in env.possible_agents:
        names = [s.name for s in env.observation_segments[a]]
        assert ("camera.depth" in names) == a.startswith("pursuer")  # evaders carry no camera
    rng = np.random.default_rng(0)
    near = 0
    for _ in range(15):
        assert space.contains(np.asarray(depth))
        for k, a in enumerate(pursuers):
            seg = next(s for s in env.observation_segments[a] if s.name == "camera.depth")
            assert seg.shape == (H, W) and seg.unit == "m"
            np.testing.assert_array_equal(depth[k], obs[a][seg.offset:seg.offset + seg.size].reshape(H, W))
        near += int((depth < RANGE).sum())
        before = depth.copy()
        obs, *_ = env.step({a: rng.uniform(-1, 1, 2) * env.action_space(a).high for a in env.agents})
        if env.agents:
            assert not np.array_equal(before, depth)  # the same memory, the next images
    assert near > 0  # the pack's obstacles and faces come into view
    env.close()


def test_the_vector_envs_show_every_games_images():
    v = peg3d.vector_env(map="maps/forest.yaml", num_envs=3, threads=2, seed=1, set=dict(SHORT, **CAMERA))
    obs, _ = v.reset(seed=1)
    depth = v.observation_view("camera.depth")
    assert set(depth) == {"pursuer"} and depth["pursuer"].shape == (3, 1, H, W)
    assert np.shares_memory(depth["pursuer"], obs["pursuer"])
    assert v.observation_view_space("camera.depth")["pursuer"].contains(np.asarray(depth["pursuer"][0]))
    with pytest.raises(KeyError, match="camera.depth"):
        peg3d.vector_env(map="maps/forest.yaml", num_envs=1, set=SHORT).observation_view("camera.depth")

    learner = peg3d.LearnerVectorEnv(num_envs=2, map="maps/forest.yaml", opponent="flee", set=dict(SHORT, **CAMERA))
    lobs, _ = learner.reset(seed=3)
    view = learner.observation_view("camera.depth")
    seg = next(s for s in learner.observation_segments if s.name == "camera.depth")
    assert view.shape == (2, H, W)  # the batch's memory (reset hands out a copy of the observations)
    np.testing.assert_array_equal(view, lobs[:, seg.offset:seg.offset + seg.size].reshape(2, H, W))
    one = peg3d.LearnerEnv(map="maps/forest.yaml", opponent="flee", set=dict(SHORT, **CAMERA))
    one.reset(seed=3)
    assert one.observation_view("camera.depth").shape == (H, W)
    np.testing.assert_array_equal(one.observation_view("camera.depth"), view[0])  # game 0 seeded as the one game
