"""PettingZoo's own tests (pettingzoo.test, the version of python/constraints.txt) on every shipped map, and on
the team maps' starts of each team size: the parallel and AEC APIs, seeding, max_cycles, rendering, state() and
the performance benchmark."""

import functools
import glob
import os
import types

import pytest
from pettingzoo.test import (api_test, max_cycles_test, parallel_api_test, parallel_seed_test,
                             performance_benchmark, render_test, seed_test, state_test)

import peg3d
from peg3d import _loading

MAPS = sorted(os.path.relpath(p, _loading.data_dir()) for p in glob.glob(str(_loading.data_dir() / "maps" / "*.yaml")))
# A map and a scenario to name (None: the map's default); pack.yaml's 2 v 2 starts are played only when named.
CASES = [(m, None) for m in MAPS] + [("maps/pack.yaml", "2v2-diagonal")]
IDS = [f"{os.path.basename(m)}{'' if s is None else ':' + s}" for m, s in CASES]


def test_every_shipped_map_is_here():
    assert len(MAPS) >= 13 and "maps/canyon.yaml" in MAPS and "maps/pack.yaml" in MAPS


@pytest.fixture(params=CASES, ids=IDS)
def case(request):
    m, scenario = request.param
    return dict(map=m, scenario=scenario)


def test_parallel_api(case):
    parallel_api_test(peg3d.parallel_env(**case), num_cycles=300)


def test_parallel_seed(case):
    parallel_seed_test(functools.partial(peg3d.parallel_env, **case), num_cycles=300)


def test_aec_api(case):
    api_test(peg3d.env(**case), num_cycles=300)


def test_aec_seed(case):
    seed_test(functools.partial(peg3d.env, **case), num_cycles=300)


def test_max_cycles(case):
    max_cycles_test(types.SimpleNamespace(parallel_env=functools.partial(peg3d.parallel_env, **case),
                                          env=functools.partial(peg3d.env, **case)))


def test_render(case, tmp_path):
    render_test(functools.partial(peg3d.env, render_path=tmp_path / "replay.html", **case))
    assert (tmp_path / "replay.html").read_text().startswith("<!DOCTYPE html>")


def test_state(case):
    state_test(peg3d.env(**case), peg3d.parallel_env(**case))


def test_performance_benchmark(case, capsys):
    performance_benchmark(peg3d.env(**case))
    out = capsys.readouterr().out
    turns = float(out.split(" turns per second")[0].split()[-1])
    print(f"{case['map']}: {turns:.0f} agent turns per second")
    assert turns > 0
