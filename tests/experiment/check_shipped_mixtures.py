#!/usr/bin/env python3
"""The self-play mixtures shipped in policies/selfplay/<map>/ play: each map's final pursuer and evader mixtures
(their members: players by name, policy files beside them) against each other in peg-matchup on maps/<map>.yaml,
with the settings they were trained with (docs/learning.md, "Self-play"). A renamed player or a missing member file
fails here. Usage: check_shipped_mixtures.py BIN_DIR SOURCE_DIR WORK_DIR"""
import csv
import pathlib
import shutil
import subprocess
import sys

SETTINGS = ["pursuer.sight.enabled=true", "evader.sight.enabled=true", "pursuer.sight.fov=120",
            "pursuer.sight.share=true", "pursuer.speed=1.0", "evader.speed=1.3", "capture_distance=0.3",
            "initial_heading=random"]


def main(bin_dir, source, work):
    bin_dir, source, work = pathlib.Path(bin_dir), pathlib.Path(source), pathlib.Path(work)
    shutil.rmtree(work, ignore_errors=True)
    shipped = sorted(d for d in (source / "policies" / "selfplay").iterdir() if d.is_dir())
    assert shipped, "no shipped mixtures"
    for d in shipped:
        out = work / d.name
        cmd = [str(bin_dir / "peg-matchup"), "--map", str(source / "maps" / f"{d.name}.yaml"),
               "--pursuers", "facl", "--pursuer-policy", str(d / "final_pursuer.json"),
               "--evaders", "facl", "--evader-policy", str(d / "final_evader.json"),
               "--repeats", "2", "--seed", "1", "--threads", "1", "--out", str(out)]
        for s in SETTINGS:
            cmd += ["--set", s]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, f"{d.name}: exit {r.returncode}\n{r.stderr}"
        rows = list(csv.DictReader(open(out / "matchups.csv")))
        assert rows and all(x["pursuer"] == "mixture" and x["evader"] == "mixture" for x in rows), d.name
        print(f"{d.name}: {len(rows)} games, {sum(int(x['captured']) for x in rows)} captures")


if __name__ == "__main__":
    main(*sys.argv[1:4])
