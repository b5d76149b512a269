"""render(): the browser replay of the episode, as peg-matchup --html writes one (docs/viewer.md)."""

import base64
import html
import json
import re

import gymnasium
import numpy as np
import pytest

import peg3d
from conftest import SHORT, play


def replay_of(path):
    text = path.read_text()
    assert text.startswith("<!DOCTYPE html>")
    data = re.search(r'<script id="peg-replay" type="application/json">(.*?)</script>', text, re.S).group(1)
    title = html.unescape(re.search(r"<title>(.*?)</title>", text).group(1))
    return json.loads(data), title


def test_render_writes_every_frame_of_the_finished_episode(tmp_path):
    out = tmp_path / "episode.html"
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=SHORT,
                             render_mode="html", render_path=out)
    assert "html" in env.metadata["render_modes"]
    record = play(env, seed=4)
    assert env.render() == str(out)
    replay, title = replay_of(out)
    steps = len(record) - 1
    assert replay["frames"] == steps + 1  # the start and every step
    assert "paper" in title and "seed 4" in title
    # every agent's track ends where the game left it (float32 positions, base64)
    states = env._batch.agent_states(0)
    for i, agent in enumerate(replay["agents"]):
        track = np.frombuffer(base64.b64decode(agent["track"]["position_f32"]), dtype="<f4").reshape(-1, 3)
        assert track.shape[0] == steps + 1
        assert np.allclose(track[-1], states[i, :3], atol=1e-4)
    env.close()


def test_render_mid_episode_writes_the_frames_so_far_and_reset_starts_afresh(tmp_path):
    out = tmp_path / "partial.html"
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=SHORT,
                             render_mode="html", render_path=out)
    play(env, seed=1, steps=5)
    env.render()
    assert replay_of(out)[0]["frames"] == 6
    env.reset(seed=2)
    env.render()
    assert replay_of(out)[0]["frames"] == 1
    env.close()


def test_render_without_a_mode_returns_none_and_a_bad_mode_is_refused(env):
    env.reset(seed=0)
    assert env.render() is None
    with pytest.raises(ValueError, match="render_mode"):
        peg3d.parallel_env(map="maps/paper.yaml", render_mode="rgb")


def test_human_mode_writes_the_replay_for_a_browser_and_returns_none(tmp_path):
    out = tmp_path / "human.html"
    env = peg3d.parallel_env(map="maps/paper.yaml", opponents={"evader": "flee"}, set=SHORT,
                             render_mode="human", render_path=out)
    play(env, seed=3, steps=4)
    assert env.render() is None
    assert replay_of(out)[0]["frames"] == 5
    env.close()


def test_render_fps_is_one_frame_a_step_of_the_configured_dt():
    for dt, fps in ((0.1, 10), (0.05, 20), (0.25, 4)):
        envs = [peg3d.parallel_env(opponents={"evader": "flee"}, set={"dt": dt}),
                gymnasium.make("peg3d/Pursuer-v0", set={"dt": dt}).unwrapped,
                gymnasium.make_vec("peg3d/Pursuer-v0", num_envs=2, vectorization_mode="vector_entry_point",
                                   set={"dt": dt})]
        for env in envs:
            assert env.metadata["render_fps"] == pytest.approx(fps), type(env).__name__
            env.close()


def test_rgb_array_gives_the_game_as_it_stands_as_an_image():
    env = peg3d.parallel_env(map="maps/forest.yaml", opponents={"evader": "flee"}, set=SHORT, render_mode="rgb_array")
    assert "rgb_array" in env.metadata["render_modes"] and env.metadata["render_fps"] == 10
    env.reset(seed=1)
    first = env.render()
    assert first.shape == (480, 640, 3) and first.dtype == np.uint8
    for _ in range(10):
        env.step({"pursuer_0": np.array([0.3, 0.0])})
    later = env.render()
    changed = np.any(first != later, axis=2)
    assert 0 < changed.sum() < 0.05 * changed.size  # the agents moved; the forest did not
    np.testing.assert_array_equal(later, env.render())  # rendering changes nothing


def test_gymnasiums_record_video_records_the_learner_env(tmp_path):
    import gymnasium as gym

    pytest.importorskip("moviepy")  # in .venv (python/constraints.txt), not in a clean environment

    env = gym.make("peg3d/Pursuer-v0", map="maps/forest.yaml", set=SHORT, render_mode="rgb_array")
    env = gym.wrappers.RecordVideo(env, str(tmp_path / "videos"), episode_trigger=lambda e: True, disable_logger=True)
    env.reset(seed=2)
    done = False
    while not done:
        _, _, term, trunc, _ = env.step(env.action_space.sample())
        done = term or trunc
    env.close()
    videos = list((tmp_path / "videos").glob("*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 1000


def test_the_vector_env_renders_every_game():
    import gymnasium as gym

    v = gym.make_vec("peg3d/Pursuer-v0", num_envs=3, vectorization_mode="vector_entry_point", set=SHORT,
                     render_mode="rgb_array")
    v.reset(seed=1)  # one seed for the batch: the games start from the map's scenarios in turn
    frames = v.render()
    assert len(frames) == 3 and all(f.shape == (480, 640, 3) for f in frames)
    assert not np.array_equal(frames[0], frames[1])  # other starts
