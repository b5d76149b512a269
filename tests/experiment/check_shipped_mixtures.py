#!/usr/bin/env python3
"""The self-play mixtures shipped in policies/selfplay/<map>/ play: each map's final pursuer and evader mixtures
(their members: players by name, policy files beside them) against each other in peg-matchup, on the map and with
the overrides of the run that trained them (its settings.json, shipped beside them). A renamed player, a missing
member file or a setting the game no longer takes fails here. Usage: check_shipped_mixtures.py BIN_DIR SOURCE_DIR
WORK_DIR"""
import csv
import json
import pathlib
import shutil
import subprocess
import sys


def main(bin_dir, source, work):
    bin_dir, source, work = pathlib.Path(bin_dir), pathlib.Path(source), pathlib.Path(work)
    shutil.rmtree(work, ignore_errors=True)
    shipped = sorted(d for d in (source / "policies" / "selfplay").iterdir() if d.is_dir())
    assert shipped, "no shipped mixtures"
    for d in shipped:
        out = work / d.name
        settings = json.loads((d / "settings.json").read_text())
        assert pathlib.Path(settings["map"]).stem == d.name, f"{d.name}: trained on {settings['map']}"
        cmd = [str(bin_dir / "peg-matchup"), "--map", str(source / settings["map"]),
               "--pursuers", "facl", "--pursuer-policy", str(d / "final_pursuer.json"),
               "--evaders", "facl", "--evader-policy", str(d / "final_evader.json"),
               "--repeats", "2", "--seed", "1", "--threads", "1", "--out", str(out)]
        for key, value in settings["set"].items():
            cmd += ["--set", f"{key}={value}"]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, f"{d.name}: exit {r.returncode}\n{r.stderr}"
        rows = list(csv.DictReader(open(out / "matchups.csv")))
        assert rows and all(x["pursuer"] == "mixture" and x["evader"] == "mixture" for x in rows), d.name
        print(f"{d.name}: {len(rows)} games, {sum(int(x['captured']) for x in rows)} captures")


if __name__ == "__main__":
    main(*sys.argv[1:4])
