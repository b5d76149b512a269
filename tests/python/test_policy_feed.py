"""A network trained from Python plays anywhere (issue 50, docs/python.md "Policy files"): the C++ player of a saved
peg3d-mlp file is fed exactly the observation the batch gives its agent (neighbour slots, sight entries, lidar
ranges: game::write_observation serves both). Nothing is trained: a random network with all of those in its
observation plays a team of pursuers (3 v 2 on maps/pack.yaml) driven from Python, by the file's documented forward
pass, and is played by the C++ side in the batch, in a peg-collide case and in peg-matchup: the same actions at
every step, the same trajectory bit for bit, the same game."""

import csv
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest

import peg3d
from test_parity import BIN, fnv1a

MAP, SCENARIO = "maps/pack.yaml", "3v2-cross"
SETTINGS = {"time_limit": 8.0, "pursuer.sight.enabled": True, "pursuer.sight.fov": 200, "evader.sight.enabled": True,
            "pursuer.lidar.azimuth_rays": 8, "pursuer.lidar.elevation_rays": 2, "pursuer.lidar.elevation_fov": 30,
            "pursuer.lidar.range": 12}
NEIGHBOURS = 2


def random_network(n_in, bound, seed=3):
    """A 2-layer network with every weight drawn, and a drawn input normalization."""
    rng = np.random.default_rng(seed)
    layers = [(rng.normal(0, 0.4, (12, n_in)), rng.normal(0, 0.1, 12)), (rng.normal(0, 0.8, (2, 12)), rng.normal(0, 0.1, 2))]
    mean, std = rng.normal(0, 1, n_in), rng.uniform(0.5, 4.0, n_in)
    return {"layers": layers, "input_mean": mean, "input_std": std, "action_bound": bound}


def forward(net, obs):
    """The file's documented forward pass, summed in the order the C++ player sums (src/players/mlp_policy.hpp):
    x = (obs - mean) * (1 / std), tanh after every layer but the last, bound * tanh(out); math.tanh is the C
    library's, as std::tanh is."""
    a = [(float(np.float32(o)) - m) * (1.0 / s) for o, m, s in zip(obs, net["input_mean"], net["input_std"])]
    for k, (w, b) in enumerate(net["layers"]):
        out = []
        for j in range(w.shape[0]):
            s = float(b[j])
            for i in range(w.shape[1]):
                s += float(w[j, i]) * a[i]
            out.append(s if k + 1 == len(net["layers"]) else math.tanh(s))
        a = out
    return np.array([net["action_bound"] * math.tanh(a[0]), net["action_bound"] * math.tanh(a[1])])


@pytest.fixture(scope="module")
def played(tmp_path_factory):
    """The network saved, and one game of it driven from Python: every frame's agent states and the pursuers'
    actions of each step."""
    env = peg3d.parallel_env(map=MAP, scenario=SCENARIO, opponents={"evader": "flee"}, set=SETTINGS,
                             neighbours=NEIGHBOURS)
    segments = env.observation_segments["pursuer_0"]
    names = [s.name for s in segments]
    assert "neighbour.teammate.1.mask" in names and "sight.age" in names and "lidar.ranges" in names
    bound = float(env.action_space("pursuer_0").high[0])
    net = random_network(sum(s.size for s in segments), bound)
    path = tmp_path_factory.mktemp("feed") / "net.json"
    peg3d.save_policy(path, role="pursuer", observation=segments, **net)
    obs, _ = env.reset(seed=0)
    frames, actions = [env._batch.agent_states(0)], []
    while env.agents:
        act = {a: forward(net, obs[a]) for a in env.agents}
        actions.append(act)
        obs, *_ = env.step(act)
        frames.append(env._batch.agent_states(0))
    info = env._batch.game_info(0)
    env.close()
    assert len(frames) > 40
    return {"path": path, "frames": frames, "actions": actions, "outcome": info["outcome"], "steps": info["step"]}


def test_the_batchs_cpp_player_takes_pythons_actions_step_by_step(played):
    v = peg3d.vector_env(map=MAP, scenario=SCENARIO, opponents={"pursuer": str(played["path"]), "evader": "flee"},
                         set=SETTINGS, neighbours=NEIGHBOURS, seed=0)
    v.reset(seed=0)
    b = v._batch
    assert np.array_equal(b.agent_states(0), played["frames"][0])
    turned = 0
    for k, act in enumerate(played["actions"]):
        v.step({})
        commands = b.agent_commands(0)
        for a, u in act.items():
            i = int(a.split("_")[1])
            np.testing.assert_allclose(commands[i], u, rtol=0, atol=1e-15, err_msg=f"step {k + 1}, {a}")
            turned += int(abs(u[0]) > 1e-3)
        assert np.array_equal(b.agent_states(0), played["frames"][k + 1]), f"frame {k + 1}"
    assert turned > len(played["actions"])  # real turns, not zeros
    assert b.game_info(0)["done"] and b.game_info(0)["step"] == played["steps"]


def test_a_collision_case_plays_the_python_driven_trajectory(played, tmp_path):
    case = tmp_path / "feed"
    case.mkdir()
    root = Path(__file__).resolve().parents[2]
    sets = "".join(f"  - {k}={str(v).lower() if isinstance(v, bool) else v}\n" for k, v in SETTINGS.items())
    agents = "".join(f"  pursuer_{k}: {{policy: {played['path']}}}\n" for k in range(3))
    agents += "".join(f"  evader_{k}: {{scripted: flee}}\n" for k in range(2))
    (case / "case.yaml").write_text(f"map: {root / MAP}\nscenario: {SCENARIO}\nset:\n{sets}agents:\n{agents}")
    subprocess.run([str(BIN / "peg-collide"), "record", str(case)], check=True, capture_output=True)
    line = [l for l in (case / "golden.log").read_text().splitlines() if l.startswith("trajectory ")][0]
    assert int(line.split()[1], 16) == fnv1a(played["frames"])


def test_peg_matchup_plays_the_same_game(played, tmp_path):
    out = tmp_path / "matchup"
    sets = [a for k, v in SETTINGS.items() for a in ("--set", f"{k}={str(v).lower() if isinstance(v, bool) else v}")]
    subprocess.run([str(BIN / "peg-matchup"), "--map", MAP, "--pursuers", "facl", "--evaders", "flee",
                    "--pursuer-policy", str(played["path"]), "--repeats", "1", "--episodes", "0", "--out", str(out),
                    "--plain-progress", *sets], check=True, capture_output=True)
    rows = [r for r in csv.DictReader(open(out / "matchups.csv")) if r["scenario"] == SCENARIO]
    assert len(rows) == 1 and rows[0]["pursuer"] == "mlp"
    assert rows[0]["outcome"] == played["outcome"]
    assert abs(float(rows[0]["episode_time_s"]) - 0.1 * played["steps"]) < 1e-9
    # The pursuers' mean path over the Python-driven frames: the same flight, not only the same ending.
    p = np.array([f[:3, :3] for f in played["frames"]])  # frames x pursuers x (x, y, z)
    path = np.linalg.norm(np.diff(p, axis=0), axis=-1).sum(axis=0).mean()
    assert abs(float(rows[0]["pursuer_path_m"]) - path) < 1e-6


def test_a_network_whose_observation_differs_is_refused_naming_the_segment(played, tmp_path):
    # The same file for a game whose pursuers carry no lidar: refused before any game, naming the first difference.
    with pytest.raises(peg3d.InputError, match=r"observation.*lidar\.ranges"):
        peg3d.vector_env(map=MAP, scenario=SCENARIO, opponents={"pursuer": str(played["path"]), "evader": "flee"},
                         set={k: v for k, v in SETTINGS.items() if "lidar" not in k}, neighbours=NEIGHBOURS)
    sets = [a for k, v in SETTINGS.items() if "lidar" not in k
            for a in ("--set", f"{k}={str(v).lower() if isinstance(v, bool) else v}")]
    r = subprocess.run([str(BIN / "peg-matchup"), "--map", MAP, "--pursuers", "facl", "--evaders", "flee",
                        "--pursuer-policy", str(played["path"]), "--repeats", "1", "--episodes", "0",
                        "--out", str(tmp_path / "refused"), *sets], capture_output=True, text=True)
    assert r.returncode == 2 and "lidar.ranges" in r.stderr and not (tmp_path / "refused").exists()
