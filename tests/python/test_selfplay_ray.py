"""peg3d.selfplay on a Ray cluster: a head and a second node started on loopback (`ray start --head`, `ray start
--address`), two tiny iterations sent to them, and the same payoff matrices and the same saved networks as the
run in this process. An unreachable address is refused before anything is written."""

import filecmp
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from peg3d import selfplay
from test_selfplay import tiny

ray = pytest.importorskip("ray")
pytest.importorskip("torch")

RAY = str(Path(sys.executable).parent / "ray")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def cluster(tmp_path):
    """Two Ray nodes of one CPU each on 127.0.0.1; the workers see this test's PYTHONPATH and data."""
    port = free_port()
    env = dict(os.environ, RAY_USAGE_STATS_ENABLED="0")
    common = ["--num-cpus", "1", "--object-store-memory", str(100 << 20), "--node-ip-address", "127.0.0.1"]
    subprocess.run([RAY, "start", "--head", "--port", str(port), "--include-dashboard", "false",
                    "--disable-usage-stats"] + common, env=env, check=True, capture_output=True, timeout=120)
    try:
        subprocess.run([RAY, "start", "--address", f"127.0.0.1:{port}"] + common, env=env, check=True,
                       capture_output=True, timeout=120)
        yield f"127.0.0.1:{port}"
    finally:
        ray.shutdown()
        subprocess.run([RAY, "stop", "--force"], env=env, capture_output=True, timeout=120)


def test_two_iterations_on_two_ray_nodes_equal_the_run_in_process(tmp_path, cluster):
    here = selfplay.SelfPlay(tiny(), tmp_path / "here", log=lambda *_: None).run()
    there = selfplay.SelfPlay(tiny(), tmp_path / "there", ray_address=cluster, log=lambda *_: None).run()
    assert there["payoff"] == here["payoff"]
    assert there == here
    nodes = {n["NodeID"] for n in ray.nodes() if n["Alive"]}
    assert len(nodes) == 2
    for root, _, files in os.walk(tmp_path / "here"):
        for f in files:
            if f != "log.jsonl":  # wall-clock times
                mine = Path(root) / f
                theirs = tmp_path / "there" / mine.relative_to(tmp_path / "here")
                assert filecmp.cmp(mine, theirs, shallow=False), mine


def test_an_unreachable_cluster_is_refused_naming_it(tmp_path):
    port = free_port()
    with pytest.raises(ConnectionError, match=f"127.0.0.1:{port}"):
        selfplay.SelfPlay(tiny(), tmp_path / "run", ray_address=f"127.0.0.1:{port}", log=lambda *_: None)
    assert not (tmp_path / "run").exists()
