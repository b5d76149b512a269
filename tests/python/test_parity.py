"""Parity with the C++ step: an episode driven from Python with the commands of a collision case has the
trajectory hash peg-collide records for that case (every agent's position and heading at every frame, bit
for bit, FNV-1a as in src/regress/collision_log.cpp)."""

import math
import subprocess
from pathlib import Path

import numpy as np

import peg3d
from conftest import BIN

ROOT = Path(__file__).resolve().parents[2]
SETTINGS = ["pursuer.guard.enabled=false", "evader.guard.enabled=false", "pursuer.motion_space=false",
            "time_limit=12"]
COMMANDS = [[0, 0, 0], [2, 6, -3], [4.5, -8, 4], [7, 0, 0]]  # time s, d_alpha deg, d_theta deg


def fnv1a(frames):
    h = 0xCBF29CE484222325
    for f in frames:
        for byte in np.ascontiguousarray(f, dtype="<f8").tobytes():
            h = ((h ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def recorded_hash(tmp_path):
    case = tmp_path / "parity"
    case.mkdir()
    rows = ", ".join(f"[{t}, {a}, {b}]" for t, a, b in COMMANDS)
    (case / "case.yaml").write_text(
        f"map: {ROOT / 'tests/collision/maps/shapes.yaml'}\nscenario: graze-hit\n"
        "set:\n" + "".join(f"  - {s}\n" for s in SETTINGS) +
        f"agents:\n  pursuer: {{commands: [{rows}]}}\n  evader: {{scripted: flee}}\n")
    subprocess.run([str(BIN / "peg-collide"), "record", str(case)], check=True, capture_output=True)
    line = [l for l in (case / "golden.log").read_text().splitlines() if l.startswith("trajectory ")][0]
    return int(line.split()[1], 16)


def command_at(t, dt):
    row = None
    for r in COMMANDS:
        if r[0] <= t + 0.5 * dt:
            row = r
    # degrees as the case reader converts them: d * pi / 180, in that order, for the same bits
    return np.zeros(2) if row is None else np.array(row[1:], dtype=np.float64) * math.pi / 180.0


def test_python_driven_episode_has_the_cpp_trajectory_hash(tmp_path):
    env = peg3d.parallel_env(map=str(ROOT / "tests/collision/maps/shapes.yaml"), scenario="graze-hit",
                             set=dict(s.split("=") for s in SETTINGS), opponents={"evader": "flee"})
    env.reset(seed=0)
    dt = env._batch.dt
    frames = [env._batch.agent_states(0)]
    k = 0
    while env.agents:
        env.step({"pursuer_0": command_at(k * dt, dt)})
        frames.append(env._batch.agent_states(0))
        k += 1
    assert k > 50
    assert fnv1a(frames) == recorded_hash(tmp_path)


def episode_frames(pursuer_set):
    """Every frame of one episode of `pn` against `flee`, both played on the C++ side, on open_wall's `ends` start."""
    base = {"pursuer.speed": "1.0", "evader.speed": "1.3", "capture_distance": "0.3", "time_limit": "40"}
    env = peg3d.VectorEnv(map=str(ROOT / "maps/open_wall.yaml"), scenario="ends", set={**base, **pursuer_set},
                          opponents={"pursuer": "pn", "evader": "flee"})
    env.reset(seed=0)
    frames = [env._batch.agent_states(0)]
    while True:
        _, _, _, _, info = env.step({})
        if info["reset"][0]:
            break
        frames.append(env._batch.agent_states(0))
    env.close()
    return frames


def test_a_classic_opponent_plays_free_of_the_motion_space_as_the_experiments_play_it():
    # The experiments play a classic player without the motion space (game::with_role_playing); so does the batch,
    # whatever the configuration says: peg3d's pursuers keep it on, and pn plays the same episode as with it off.
    on, off = episode_frames({}), episode_frames({"pursuer.motion_space": "false"})
    assert len(on) > 50
    assert fnv1a(on) == fnv1a(off)
