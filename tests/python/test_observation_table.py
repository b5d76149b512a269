"""docs/python.md's table of observation segments is the module's: the 20 base entries with their units, and a
row for every segment an agent has with neighbours, limited sight, a lidar and a depth camera, in the same order
and with the same unit and size."""

import pathlib
import re

import numpy as np

import peg3d
from conftest import SHORT

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md"
EVERYTHING = dict(SHORT, **{"pursuer.sight.enabled": True, "evader.sight.enabled": True,
                            "pursuer.lidar.azimuth_rays": 8, "pursuer.lidar.elevation_rays": 2,
                            "pursuer.camera.width": 4, "pursuer.camera.height": 3, "pursuer.camera.range": 9})


def documented_rows():
    text = DOC.read_text()
    section = text[text.index("## Observations\n"):text.index("## Policy files")]
    rows = []
    for line in section.splitlines():
        m = re.match(r"\| `([^`]+)` \|\s*([^|]*?)\s*\|\s*([^|]*?)\s*\|", line)
        if m:
            rows.append((m.group(1), m.group(2).strip(), m.group(3).strip()))
    return rows


def pattern(name):
    """A documented name as a regular expression: M stands for a slot number."""
    return re.compile(re.escape(name).replace("\\.M\\.", r"\.\d+\.") + "$")


def test_the_documented_base_entries_are_the_modules():
    rows = documented_rows()
    assert [(n, u) for n, _s, u in rows[:20]] == [(n, u) for n, u, _m in peg3d.OBSERVATION_ENTRIES]
    assert all(size == "1" for _n, size, _u in rows[:20])


def test_every_segment_of_a_fully_sensing_agent_has_its_row_in_order():
    env = peg3d.parallel_env(map="maps/pack.yaml", scenario="3v2-cross", set=EVERYTHING)
    rows = documented_rows()
    for agent in ("pursuer_0", "evader_0"):
        order = []
        for seg in env.observation_segments[agent]:
            found = [k for k, (n, _s, _u) in enumerate(rows) if pattern(n).match(seg.name)]
            assert found, f"{seg.name} has no row in docs/python.md's table"
            k = found[0]
            _name, size, unit = rows[k]
            assert unit == seg.unit, seg.name
            assert size == str(seg.size) or not size.isdigit(), seg.name
            if k not in order:
                order.append(k)
        # each row's first use in the documented order (a neighbour's offset and mask rows alternate per slot)
        assert order == sorted(order), f"{agent}'s segments are not in the documented order"
    names = [s.name for s in env.observation_segments["pursuer_0"]]
    assert "camera.depth" in names and "lidar.ranges" in names and "sight.age" in names
    assert "neighbour.teammate.1.mask" in names


def test_each_agents_space_holds_its_segments_bounds_entry_by_entry():
    # Under NumPy 2, a module built with pybind11 older than 2.12 gave every entry the first one's bounds.
    env = peg3d.parallel_env(map="maps/pack.yaml", scenario="3v2-cross", set=EVERYTHING)
    for agent in env.possible_agents:
        space = env.observation_space(agent)
        for seg in env.observation_segments[agent]:
            np.testing.assert_array_equal(space.low[seg.slice], seg.low, err_msg=seg.name)
            np.testing.assert_array_equal(space.high[seg.slice], seg.high, err_msg=seg.name)
        assert len(set(space.high.tolist())) > 5
