"""Mixtures of C++ players (`opponents={"evader": {"flee": 3, "random": 1}}`): one member drawn per episode by
weight, a role's agents together, from the seed alone; refused with the member or weight named."""

import json
import math
import pickle

import gymnasium as gym
import numpy as np
import pytest

import peg3d
from conftest import SHORT

MIXTURE = {"evader": {"flee": 3, "random": 1.0, "hide": 0}}


def drawn(env, seeds):
    """The evaders' members after reset(seed=s) for each seed: (seeds x games, evaders)."""
    out = []
    for s in seeds:
        env.reset(seed=s)
        out.append(env.members()["evader"])
    return np.concatenate(out)


def test_members_are_drawn_by_weight_and_a_roles_agents_draw_together():
    env = peg3d.vector_env(map="maps/pack.yaml", num_envs=32, opponents=MIXTURE, set=SHORT)
    assert env.controlled["evader"].all() and not env.controlled["pursuer"].any()
    m = drawn(env, range(50))
    assert (env.members()["pursuer"] == -1).all()
    assert (m[:, 0] == m[:, 1]).all()  # the team plays one member
    assert not (m == 2).any()          # weight 0
    share, n = (m[:, 0] == 0).mean(), len(m)
    assert abs(share - 0.75) < 5 * math.sqrt(0.75 * 0.25 / n), share


def test_the_draws_follow_the_seed_not_the_threads():
    one = peg3d.vector_env(map="maps/pack.yaml", num_envs=8, threads=1, opponents=MIXTURE, set=SHORT)
    two = peg3d.vector_env(map="maps/pack.yaml", num_envs=8, threads=2, opponents=MIXTURE, set=SHORT)
    assert (drawn(one, range(10)) == drawn(two, range(10))).all()
    other = drawn(one, range(10, 20))
    assert not (other == drawn(two, range(10))).all()


def test_a_learner_meets_a_mixture_and_it_pickles():
    env = gym.make("peg3d/Pursuer-v0", opponent={"flee": 1, "random": 1}, set=SHORT)
    env.reset(seed=3)
    for _ in range(5):
        env.step(env.action_space.sample())
    copy = pickle.loads(pickle.dumps(env))
    a, _ = env.reset(seed=4)
    b, _ = copy.reset(seed=4)
    assert np.array_equal(a, b)


@pytest.mark.parametrize("mixture, error, message", [
    ({"flee": 1, "random": -1}, ValueError, r"opponents\.evader\.1\.weight"),
    ({"flee": 1, "random": float("nan")}, ValueError, r"opponents\.evader\.1\.weight"),
    ({"flee": 1, "random": "1"}, TypeError, r"opponents\.evader\.1\.weight"),
    ({"flee": 1, "random": True}, TypeError, r"opponents\.evader\.1\.weight"),
    ({"flee": 0, "random": 0}, ValueError, r"opponents\.evader: a mixture's weights sum"),
    ({}, ValueError, r"opponents\.evader: a mixture has at least one member"),
    ([("flee", 1, 2)], TypeError, r"opponents\.evader: a mixture is"),
    ({"flee": 1, "no-such-player": 1}, peg3d.InputError, r"opponents\.evader\.1"),
    ({"flee": 1, "pure-pursuit": 1}, peg3d.InputError, r"opponents\.evader\.1"),
    ({"flee": 1e308, "random": 1e308}, peg3d.InputError, r"opponents\.evader"),
    (3, TypeError, r"opponents\.evader"),
])
def test_a_bad_mixture_is_refused_naming_it(mixture, error, message):
    with pytest.raises(error, match=message):
        peg3d.vector_env(opponents={"evader": mixture})


@pytest.mark.parametrize("change, field", [
    ({"version": 2}, "version"), ({"role": "referee"}, "role"), ({"members": []}, "members"),
    ({"members": [{"policy": "flee", "weight": -1}]}, r"members\.0\.weight"),
    ({"members": [{"policy": "flee", "weight": float("nan")}]}, "not JSON"),  # json.dumps writes NaN, no JSON
    ({"members": [{"policy": "flee", "weight": True}]}, r"members\.0\.weight"),
    ({"members": [{"policy": "flee", "weight": 0}]}, "members: total weight 0: the members' weights sum"),
    ({"members": [{"policy": "flee", "weight": 1}, {"policy": 3, "weight": 1}]}, r"members\.1\.policy"),
    ({"members": [{"policy": "inner.json", "weight": 1}]}, r"members\.0\.policy: inner\.json is a mixture"),
    ({"members": [{"policy": "flee", "weight": 1}] * 257}, "members: 257 members: a mixture has at most 256"),
])
def test_read_policy_refuses_a_bad_mixture_file_naming_its_field(tmp_path, change, field):
    doc = {"format": "peg3d-mixture", "version": 1, "role": "evader", "members": [{"policy": "flee", "weight": 1}]}
    (tmp_path / "inner.json").write_text(json.dumps(doc))
    (tmp_path / "mix.json").write_text(json.dumps({**doc, **change}))
    # The C++ loader's message: the file, the line when it has one, the field.
    with pytest.raises(peg3d.InputError, match=rf"mix\.json(:\d+)?: {field}"):
        peg3d.read_policy(tmp_path / "mix.json")
    assert peg3d.read_policy(tmp_path / "inner.json")["members"][0] == {"policy": "flee", "weight": 1, "path": None,
                                                                       "document": None}
