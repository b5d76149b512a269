#!/usr/bin/python3
"""End-to-end checks of the experiment binaries' command line:
- peg-matchup plays teams on maps/pack.yaml and writes matchups.csv, agents.csv and summary.json, and saves the
  sensing agents' maps of the games --save-maps chooses;
- peg-league trains teams on maps/pack.yaml and writes its matrix, findings, policies and heat-map, plays
  on a held-out map, and rejects bad algorithms, headings, policies, maps, fields and counts;
- every input error exits with status 2, prints 'error: ...' naming the file or flag, and writes nothing:
  a malformed policy file, an evader's policy passed as the pursuer's, a start within an agent's radius of
  an obstacle, a scenario name that climbs out of --out, a configuration file with an unknown key, a policy
  that cannot play its role;
- figures are drawn into an --out path with spaces and quotes (no shell in between);
- the programs carry no path into the source tree and run from a copy of build/bin and build/share;
- peg-throughput reports the mover contact searches that gave up (a ball orbiting a standing evader a hair away);
- peg-map check says which keyframe rate it chose for a map that sets none.

usage: check_cli.py BUILD_BIN_DIR SOURCE_DIR WORK_DIR
"""
import csv
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import check, run, verdict  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def main():
    bin_dir, source, work = sys.argv[1:4]
    # Builds with assertions or sanitizers name their source files in diagnostics: only a Release build
    # is checked for paths into the source tree (the relocated copy below runs either way).
    release = "--release" in sys.argv[4:]
    matchup, paper = os.path.join(bin_dir, "peg-matchup"), os.path.join(bin_dir, "peg-paper")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(source)
    # Worlds are built once, into a cache of the test's own (not the user's): under the sanitizers building
    # pack.yaml's world takes 2 s a process. The calls further down that pass --no-cache still build theirs.
    os.environ["PEG3D_CACHE_DIR"] = os.path.join(work, "cache")
    quick = ["--repeats", "1", "--episodes", "2", "--plain-progress"]

    # Teams: 3 v 2 and 2 v 2 scenarios, every pursuer policy against every evader policy.
    out = os.path.join(work, "pack")
    r = run([matchup, "--map", "maps/pack.yaml", "--out", out, *quick])
    check(r.returncode == 0, f"peg-matchup on pack.yaml: status {r.returncode}: {r.stderr[-2000:]}")
    if r.returncode == 0:
        games = rows(os.path.join(out, "matchups.csv"))
        agents = rows(os.path.join(out, "agents.csv"))
        check(len(games) == 4 * 16, f"matchups.csv has {len(games)} games, expected 64")
        check(len(agents) == (5 + 5 + 4 + 4) * 16, f"agents.csv has {len(agents)} rows, expected 288")
        check({a["role"] for a in agents} == {"pursuer", "evader"}, "agents.csv roles")
        summary = json.load(open(os.path.join(out, "summary.json")))
        check(len(summary) == 16, "one summary entry per policy pair")
        for entry in summary:
            check(entry["evaders"] == 8, f"{entry['pursuer']}/{entry['evader']}: 8 evaders over 4 games")
            for key in ("evaders_captured", "evader_capture_rate", "time_to_each_capture_s", "capture_time_s",
                        "pursuer_path_m", "evader_path_m", "collision_runs"):
                check(key in entry, f"summary.json {key}")
        check("evaders" in r.stdout, "team table on stdout")

    # --save-maps: the sensing agents' own maps of the chosen games, as OctoMap .bt files, and no others.
    out = os.path.join(work, "maps_saved")
    sensing = []
    for role in ("pursuer", "evader"):
        sensing += ["--set", f"{role}.lidar.azimuth_rays=16", "--set", f"{role}.lidar.elevation_rays=2",
                    "--set", f"{role}.lidar.elevation_fov=40", "--set", f"{role}.map.enabled=true"]
    r = run([matchup, "--map", "maps/forest.yaml", "--out", out, "--pursuers", "pn", "--evaders", "flee,random",
             "--save-maps", "F1_r0_pn_vs_flee", "--set", "time_limit=5", *sensing, *quick])
    check(r.returncode == 0, f"peg-matchup --save-maps: status {r.returncode}: {r.stderr[-2000:]}")
    if r.returncode == 0:
        saved = sorted(os.listdir(os.path.join(out, "maps")))
        check(saved == ["F1_r0_pn_vs_flee_evader_0.bt", "F1_r0_pn_vs_flee_pursuer_0.bt"], f"saved maps: {saved}")
        for f in saved:
            head = open(os.path.join(out, "maps", f), "rb").read(64)
            check(head.startswith(b"# Octomap OcTree binary file"), f"{f} is an OctoMap binary tree")

    # A policy to misuse: an evader saved by a tiny peg-paper run.
    base = os.path.join(work, "base")
    r = run([paper, "--out", base, "--algorithms", "peg3d", "--no-plots", *quick])
    check(r.returncode == 0, f"peg-paper: {r.stderr[-2000:]}")
    evader_policy = os.path.join(base, "policies", "S1_peg3d_evader.json")

    maps = os.path.join(work, "maps")
    os.makedirs(maps)
    write(os.path.join(maps, "tight.yaml"),
          "arena: {size: [10, 10, 10]}\nobstacles:\n  - {kind: sphere, center: [5, 5, 5], radius: 1}\n"
          "scenarios:\n  - name: tight\n    pursuer: {position: [5, 5, 6.1]}\n    evader: {position: [9, 9, 9]}\n")
    write(os.path.join(maps, "climb.yaml"),
          "arena: {size: [10, 10, 10]}\nscenarios:\n  - name: ../../x\n"
          "    pursuer: {position: [1, 1, 1]}\n    evader: {position: [9, 9, 9]}\n")
    write(os.path.join(maps, "bad_policy.json"), '{"format": "peg3d-policy", "version": 1, "role": "pursuer"')
    write(os.path.join(maps, "bad_config.json"), '{"pursuer": {"speeed": 2.0}}')
    bad = os.path.join(work, "bad")
    cases = [
        (matchup, ["--pursuer-policy", os.path.join(maps, "bad_policy.json")], "bad_policy.json"),
        (matchup, ["--pursuer-policy", evader_policy], "S1_peg3d_evader.json"),
        (matchup, ["--map", os.path.join(maps, "tight.yaml")], "tight.yaml:6"),
        (paper, ["--map", os.path.join(maps, "tight.yaml")], "tight.yaml:6"),
        (paper, ["--map", os.path.join(maps, "climb.yaml")], "climb.yaml:3"),
        (matchup, ["--config", os.path.join(maps, "bad_config.json")], "pursuer.speeed"),
        (matchup, ["--set", "pursuer.policy=flee"], "pursuer.policy"),
        (matchup, ["--pursuers", "facl,flee"], "--pursuers"),
        (paper, ["--algorithms", "peg3d,peg3d"], "listed twice"),
    ]
    for binary, args, named in cases:
        shutil.rmtree(bad, ignore_errors=True)
        r = run([binary, "--out", bad, *quick, *args])
        what = f"{os.path.basename(binary)} {' '.join(args)}"
        check(r.returncode == 2, f"{what}: status {r.returncode}, expected 2 ({r.stderr[-500:]})")
        check(r.stderr.startswith("error:") and named in r.stderr, f"{what}: message names {named!r}: {r.stderr[:300]!r}")
        check(not os.path.exists(bad), f"{what}: nothing written")
    r = run([os.path.join(bin_dir, "peg-map"), "check", os.path.join(maps, "tight.yaml"), "--no-cache"])
    check(r.returncode == 2 and "tight.yaml:6" in r.stderr, f"peg-map check reports the start that does not fit: {r.stderr}")
    check(not os.path.exists(os.path.join(work, "x")) and not os.path.exists(os.path.join(source, "x")),
          "a scenario named ../../x wrote nothing outside --out")

    # peg-map movers: every mover every K-th substep, as CSV; export --time marks the movers.
    r = run([os.path.join(bin_dir, "peg-map"), "movers", "maps/patrol.yaml", "--seconds", "2", "--every", "48"])
    lines = r.stdout.splitlines()
    check(r.returncode == 0 and lines[0] == "t,id,kind,x,y,z,qw,qx,qy,qz", f"peg-map movers header: {r.stderr[-300:]}")
    check(len(lines) == 1 + 11 * 5, f"peg-map movers: {len(lines) - 1} rows for 5 movers at 11 instants")
    bt0, bt12 = os.path.join(work, "patrol.bt"), os.path.join(work, "patrol_12s.bt")
    r0 = run([os.path.join(bin_dir, "peg-map"), "export", "maps/patrol.yaml", "--octree", bt0])
    r12 = run([os.path.join(bin_dir, "peg-map"), "export", "maps/patrol.yaml", "--octree", bt12, "--time", "12"])
    check(r0.returncode == 0 and r12.returncode == 0, "peg-map export with and without --time")
    if r0.returncode == 0 and r12.returncode == 0:
        check(os.path.getsize(bt12) > os.path.getsize(bt0), "the octree at 12 s holds the movers' voxels too")

    # peg-generalize reports a map without a `name` by its file name.
    write(os.path.join(maps, "nameless.yaml"),
          "arena: {size: [35, 35, 20]}\nscenarios:\n  - name: n1\n    pursuer: {position: [5, 30, 2]}\n"
          "    evader: {position: [5, 5, 2]}\n")
    gen = os.path.join(work, "gen")
    r = run([os.path.join(bin_dir, "peg-generalize"), "--out", gen, *quick, "--eval-maps",
             f"maps/paper.yaml,{os.path.join(maps, 'nameless.yaml')}"])
    check(r.returncode == 0, f"peg-generalize: {r.stderr[-500:]}")
    if r.returncode == 0:
        summary = {e["map"]: e for e in json.load(open(os.path.join(gen, "summary.json")))}
        check(set(summary) == {"paper", "nameless"}, f"generalization maps {sorted(summary)}")
        check(summary.get("nameless", {}).get("runs") == 4, "the nameless map's 4 games are reported")

    # peg-league: teams on pack.yaml (trained teams and classic ones in one matrix), the heat-map, the trained
    # policies; a held-out map; input errors exit 2 and write nothing.
    league = os.path.join(bin_dir, "peg-league")
    lg = os.path.join(work, "league")
    r = run([league, "--map", "maps/pack.yaml", "--out", lg, "--algorithms", "peg3d,robust", "--train-seeds", "2",
             "--eval-seeds", "1", "--episodes", "2", "--plain-progress", "--no-cache"])
    check(r.returncode == 0 and "warning" not in r.stderr, f"peg-league on pack.yaml: status {r.returncode}: {r.stderr[-2000:]}")
    if r.returncode == 0:
        games = rows(os.path.join(lg, "games.csv"))
        # 4 trained + 3 classic per role, 4 team starts, 1 evaluation seed.
        check(len(games) == 7 * 7 * 4, f"games.csv has {len(games)} games, expected 196")
        matrix = rows(os.path.join(lg, "matrix.csv"))
        check(len(matrix) == 5 * 5, f"matrix.csv has {len(matrix)} group pairings, expected 25")
        check(all(int(m["games"]) > 0 for m in matrix), "every group pairing played")
        check(len(rows(os.path.join(lg, "matrix_entrants.csv"))) == 49, "matrix_entrants.csv: 49 pairings")
        summary = json.load(open(os.path.join(lg, "summary.json")))
        check({f["algorithm"] for f in summary["findings"]["pursuers"]} == {"peg3d", "robust"}, "findings per algorithm")
        check(os.path.exists(os.path.join(lg, "league.png")), "league.png drawn")
        check(os.path.exists(os.path.join(lg, "league_learning.png")), "league_learning.png drawn")
        check(os.path.exists(os.path.join(lg, "policies", "robust_1_evader.json")), "trained policies saved")
        check(not os.path.exists(os.path.join(lg, "runs.journal")), "the journal is removed once the results are written")
        # Every training episode: 2 algorithms x 2 training seeds x 2 episodes, from the scenarios in turn.
        curves = rows(os.path.join(lg, "learning_curves.csv"))
        check(len(curves) == 8, f"learning_curves.csv has {len(curves)} episodes, expected 8")
        check([(c["algorithm"], c["train_seed"], c["episode"], c["scenario"]) for c in curves[:2]] ==
              [("peg3d", "0", "0", "3v2-corners"), ("peg3d", "0", "1", "3v2-cross")], "learning_curves.csv order")
        check(all(c["pool_opponent"] == "" for c in curves if c["algorithm"] == "peg3d"), "peg3d co-learns")
        check(any(c["pool_opponent"] for c in curves if c["algorithm"] == "robust"), "robust meets the pool")
        check({c["pool_opponent"] for c in curves} <= {"", "pure-pursuit", "pn", "apollonius", "flee",
                                                      "flee-apollonius", "random"}, "pool opponents by policy name")
    # A held-out map, and a saved MLP pursuer (the shipped PPO network) entering the league.
    ppo = "tests/data/policies/ppo_pursuer.json"
    r = run([league, "--out", os.path.join(work, "league2"), "--train-seeds", "1", "--eval-seeds", "1", "--episodes", "1",
             "--eval-maps", "maps/paper.yaml,maps/forest.yaml", "--pursuer-entrant", "ppo=" + ppo, "--no-plots",
             "--plain-progress", "--no-cache"])
    check(r.returncode == 0, f"peg-league on a held-out map: {r.stderr[-500:]}")
    if r.returncode == 0:
        games = rows(os.path.join(work, "league2", "games.csv"))
        maps_played = {g["map"] for g in games}
        check(maps_played == {"paper", "forest"}, f"games on {sorted(maps_played)}")
        evaders = {g["evader"] for g in games}  # peg3d#0, robust#0 and the 3 scripted ones
        check(len(evaders) == 5 and sum(g["pursuer"] == "ppo" for g in games) == 8 * len(evaders),
              "the saved pursuer plays every start (8) against every evader")
        setup = json.load(open(os.path.join(work, "league2", "run_info.json")))["setup"]
        check(setup["saved_pursuers"][0]["kind"] == "mlp", "run_info names the saved entrant's kind")
    # peg-matchup plays the MLP in the facl slot and names it by its kind.
    mu = os.path.join(work, "matchup_mlp")
    r = run([matchup, "--out", mu, "--pursuer-policy", ppo, "--pursuers", "facl,pure-pursuit", "--evaders", "flee",
             "--repeats", "1", "--plain-progress", "--no-cache"])
    check(r.returncode == 0, f"peg-matchup --pursuer-policy MLP: {r.stderr[-500:]}")
    if r.returncode == 0:
        check({g["pursuer"] for g in rows(os.path.join(mu, "matchups.csv"))} == {"mlp", "pure-pursuit"},
              "matchups.csv names the MLP slot mlp")
    for args, named in [(["--algorithms", "peg3d,nonsense"], "nonsense"), (["--eval-heading", "sideways"], "--eval-heading"),
                        (["--train-heading", "backwards"], "--train-heading"),
                        (["--evaders", "flee,pn"], "--evaders"), (["--eval-maps", os.path.join(maps, "tight.yaml")], "tight.yaml:6"),
                        (["--set", "training.pool.share=2"], "training.pool.share"), (["--train-seeds", "0"], "--train-seeds"),
                        (["--evader-entrant", ppo], "ppo_pursuer.json"), (["--pursuer-entrant", "pn=" + ppo], "--pursuer-entrant"),
                        (["--pursuer-entrant", "x=missing.json"], "missing.json")]:
        shutil.rmtree(bad, ignore_errors=True)
        r = run([league, "--out", bad, "--episodes", "1", "--plain-progress", "--no-cache", *args])
        what = f"peg-league {' '.join(args)}"
        check(r.returncode == 2, f"{what}: status {r.returncode}, expected 2 ({r.stderr[-500:]})")
        check(r.stderr.startswith("error:") and named in r.stderr, f"{what}: message names {named!r}: {r.stderr[:300]!r}")
        check(not os.path.exists(bad), f"{what}: nothing written")

    # peg-throughput counts the mover contact searches that gave up: a ball orbits a standing evader in 0.01 s,
    # 1.5e-4 m from its sphere (radius 0.25), so no search can finish within its bound; each answers a collision.
    write(os.path.join(maps, "orbit.yaml"),
          "arena: {size: [35, 35, 20]}\nmovers:\n  - kind: sphere\n    radius: 1.0\n"
          "    orbit: {center: [12, 12, 10], radius: 1.25015, period: 0.01}\n"
          "start:\n  pursuer: {position: [30, 30, 10]}\n  evader: {position: [12, 12, 10]}\n")
    r = run([os.path.join(bin_dir, "peg-throughput"), "--map", os.path.join(maps, "orbit.yaml"), "--steps", "20",
             "--no-breakdown", "--no-cache", "--set", "evader.speed=0", "--set", "evader.guard.enabled=false"])
    check(r.returncode == 0, f"peg-throughput on orbit.yaml: status {r.returncode}: {r.stderr[-500:]}")
    if r.returncode == 0:
        t = json.loads(r.stdout)
        check(t["contact_give_ups"] == t["episodes"] == 20,
              f"peg-throughput reports one give-up per one-step episode: {t['contact_give_ups']} in {t['episodes']}")

    # A map that sets no keyframe rate runs at the highest that fits the motion budget, and peg-map check says
    # which; the same map asking for every substep is refused as before. 200 bodies over the default game:
    # every substep would need about 304 MiB of the 256.
    balls = "".join(f"  - {{kind: sphere, radius: 0.3, dynamic: {{position: [{2 + k % 15 * 2.2:.2f}, "
                    f"{2 + k // 15 * 2.2:.2f}, 0.3], mass: 2}}}}\n" for k in range(200))
    head = "arena: {size: [35, 35, 20]}\nstart: {pursuer: {position: [1, 1, 19]}, evader: {position: [34, 34, 19]}}\n"
    write(os.path.join(maps, "bodies_200.yaml"), head + "movers:\n" + balls)
    write(os.path.join(maps, "bodies_200_every.yaml"), head + "physics: {keyframe_hz: 0}\nmovers:\n" + balls)
    peg_map = os.path.join(bin_dir, "peg-map")
    r = run([peg_map, "check", os.path.join(maps, "bodies_200.yaml"), "--no-cache"])
    check(r.returncode == 0 and "keyframes  120/s (one every 2 substeps), chosen: the map sets no physics.keyframe_hz"
          in r.stdout, f"peg-map check chooses 120 keyframes/s: status {r.returncode}: {r.stdout[-600:]}{r.stderr[-300:]}")
    r = run([peg_map, "check", os.path.join(maps, "bodies_200_every.yaml"), "--no-cache"])
    check(r.returncode == 2 and "bodies_200_every.yaml:3: physics.keyframe_hz:" in r.stderr,
          f"a map that asks for every substep over the budget is refused: {r.returncode}: {r.stderr[:300]}")

    # Figures into a folder whose name a shell would split and unquote.
    odd = os.path.join(work, "it's a \"folder\" $HOME")
    r = run([paper, "--out", odd, "--algorithms", "peg3d", *quick])
    check(r.returncode == 0 and "warning" not in r.stderr, f"plots into an odd --out: {r.stderr[-500:]}")
    for fig in ("trajectories.png", "comparison.png"):
        check(os.path.exists(os.path.join(odd, fig)), f"{fig} drawn into {odd}")

    # No path into the source tree; a copy of the build's bin/ and share/ runs from anywhere.
    for name in ("peg-paper", "peg-matchup", "peg-generalize", "peg-league", "peg-map") if release else ():
        check(os.path.realpath(source).encode() not in open(os.path.join(bin_dir, name), "rb").read(),
              f"{name} holds no path into the source tree")
    copy = os.path.join(work, "install")
    shutil.copytree(os.path.join(bin_dir, "..", "share"), os.path.join(copy, "share"))
    os.makedirs(os.path.join(copy, "bin"))
    shutil.copy2(paper, os.path.join(copy, "bin", "peg-paper"))
    elsewhere = os.path.join(work, "elsewhere")
    os.makedirs(elsewhere)
    env = {k: v for k, v in os.environ.items() if k != "PEG3D_DATA_DIR"}
    r = run([os.path.join(copy, "bin", "peg-paper"), "--out", "res", "--algorithms", "peg3d", *quick], cwd=elsewhere, env=env)
    check(r.returncode == 0, f"a copied peg-paper with its share/ runs from another folder: {r.stderr[-500:]}")
    check(os.path.exists(os.path.join(elsewhere, "res", "trajectories.png")), "and draws its figures")

    return verdict()


if __name__ == "__main__":
    sys.exit(main())
