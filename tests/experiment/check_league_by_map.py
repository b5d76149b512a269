#!/usr/bin/env python3
"""tools/league_by_map.py on a games.csv made by hand, whose answers are known: the Wilson interval, the paired
capture-time difference over the games both pursuers won, and the paired capture-rate difference over every
game both played.

    check_league_by_map.py SOURCE_DIR WORK_DIR
"""

import csv
import math
import os
import subprocess
import sys


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, "games.csv")
    # 40 paired games on two starts: "ref" catches in 20 of them (at 10 s), "new" in 30 (at 8 s): the 20 of
    # ref's and 10 more. A per-game difference of 1 in 10 games, 0 in 30: mean 0.25, standard error
    # sqrt(0.25 * 0.75 * 40 / 39 / 40).
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["map", "scenario", "eval_seed", "pursuer", "evader", "captured", "capture_time_s"])
        for g in range(40):
            scenario, seed = ("S1", "S2")[g % 2], str(g // 2)
            w.writerow(["m", scenario, seed, "ref", "flee", int(g < 20), "10.0" if g < 20 else ""])
            w.writerow(["m", scenario, seed, "new", "flee", int(g < 30), "8.0" if g < 30 else ""])
    out = subprocess.run([sys.executable, os.path.join(source, "tools", "league_by_map.py"), path,
                          "--reference", "ref", "--markdown"], check=True, capture_output=True, text=True).stdout
    rows = {line.split("|")[2].strip(): [c.strip() for c in line.split("|")[1:-1]]
            for line in out.splitlines()[2:]}
    assert rows["ref"][7] == "-" and rows["ref"][8] == "-", rows["ref"]
    assert rows["new"][3] == "40", rows["new"]
    assert rows["new"][4].startswith("0.750 ["), rows["new"]
    # Every shared capture is 2 s sooner, with no spread.
    assert rows["new"][7] == "-2.0 s [-2.0, -2.0]", rows["new"]
    se = math.sqrt(0.25 * 0.75 * 40 / 39 / 40)
    want = f"{0.25:+.3f} [{0.25 - 1.959963984540054 * se:+.3f}, {0.25 + 1.959963984540054 * se:+.3f}]"
    assert rows["new"][8] == want, (rows["new"][8], want)
    print("league_by_map: paired differences as computed by hand")


if __name__ == "__main__":
    main()
