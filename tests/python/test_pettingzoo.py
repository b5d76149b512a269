"""PettingZoo's own tests (pettingzoo.test, the version of python/constraints.txt) on every shipped map, and on
the team maps' starts of each team size: the parallel and AEC APIs, seeding, max_cycles, rendering and state();
and its performance benchmark on two maps (below)."""

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


# PettingZoo's benchmark asserts nothing and runs 5 s a call: here on the map of the paper and on the heaviest,
# quarry (520 bodies, 120 movers). Any other map runs it with
#     .venv/bin/python -c "import peg3d; from pettingzoo.test import performance_benchmark as b; \
#         b(peg3d.env(map='maps/forest.yaml'))"
BENCHMARKED = [c for c in CASES if c[0] in ("maps/paper.yaml", "maps/quarry.yaml") and c[1] is None]


@pytest.mark.parametrize("map, scenario", BENCHMARKED, ids=[os.path.basename(m) for m, _ in BENCHMARKED])
def test_performance_benchmark(map, scenario, capsys):
    case = dict(map=map, scenario=scenario)
    performance_benchmark(peg3d.env(**case))
    out = capsys.readouterr().out
    turns = float(out.split(" turns per second")[0].split()[-1])
    print(f"{case['map']}: {turns:.0f} agent turns per second")
    assert turns > 0
