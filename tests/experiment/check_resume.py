#!/usr/bin/python3
"""End-to-end checks of sweeps that survive interruption (docs/results.md, "Journal and resume"):
- a sweep killed mid-way with SIGKILL keeps its finished runs in OUT/runs.journal and writes no result file;
  --resume (on another thread count, after a torn last line was appended) finishes it with result files
  byte-identical to an uninterrupted sweep's: peg-paper killed on 1 thread and on 2, peg-matchup and
  peg-generalize once each, and peg-matchup with lidars, own maps and sight writing every replay;
- SIGINT stops a sweep within 2 s with status 130, says what was kept and prints the command that resumes
  it; that command finishes the sweep identically; SIGTERM exits with 143;
- peg-league stopped with SIGTERM while it plays its games keeps its training runs and resumes identically;
- a finished sweep removes its journal; an existing journal without --resume, --resume without a journal and
  --resume with another seed are input errors (status 2) that name the problem.

usage: check_resume.py BUILD_BIN_DIR SOURCE_DIR WORK_DIR [--sanitized]
"""
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import check, failures, run, verdict  # noqa: E402
from result_folders import journal_runs, same_results, small_sweeps, wait_for_runs  # noqa: E402


def start(cmd):
    # A script's background job inherits SIGINT ignored (and peg3d leaves an ignored signal ignored, as a
    # shell's background job expects): give the sweep the default disposition, as a terminal would.
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))


def killed_then_resumed(name, cmd, out, reference, threads, resume_threads, tear, after=5):
    """SIGKILL once `after` runs are journaled, optionally tear the last line, resume on another thread count."""
    shutil.rmtree(out, ignore_errors=True)
    proc = start(cmd + ["--out", out, "--threads", str(threads)])
    if not check(wait_for_runs(proc, out, after), f"{name}: killed mid-way (the sweep ended before {after} runs were "
                                                  f"journaled: status {proc.poll()}; raise its budget)"):
        proc.kill()
        proc.wait()
        return
    proc.kill()  # SIGKILL
    proc.wait()
    kept = journal_runs(out)
    check(not os.path.exists(os.path.join(out, "summary.json")), f"{name}: no result file after SIGKILL")
    if tear:  # a crash in the middle of writing a line
        with open(os.path.join(out, "runs.journal"), "ab") as f:
            f.write(b'{"run":0,"data":{"evaluation":[0,12')
    failed = len(failures)
    r = run(cmd + ["--out", out, "--threads", str(resume_threads), "--resume"])
    check(r.returncode == 0, f"{name}: --resume status {r.returncode}: {r.stderr[-800:]}")
    m = re.search(r"resuming: (\d+) of (\d+) runs", r.stderr)
    check(m is not None and int(m.group(1)) == kept, f"{name}: resume reads back the {kept} journaled runs: {r.stderr[:300]!r}")
    check(not tear or "torn last line" in r.stderr, f"{name}: the torn last line is reported and dropped")
    check(not os.path.exists(os.path.join(out, "runs.journal")), f"{name}: the finished sweep removed its journal")
    same_results(reference, out, f"{name} (killed on {threads} thread(s), resumed on {resume_threads})")
    if len(failures) == failed:
        print(f"{name}: killed with {kept} of {m.group(2)} runs journaled, resumed identically")


def main():
    bin_dir, source, work = sys.argv[1:4]
    sanitized = "--sanitized" in sys.argv[4:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(source)
    # Worlds are built once, into a cache of the test's own (not the user's).
    os.environ["PEG3D_CACHE_DIR"] = os.path.join(work, "cache")
    t0 = time.monotonic()

    sweeps = small_sweeps(bin_dir)
    references = {}
    for name, cmd in sweeps.items():
        references[name] = os.path.join(work, f"{name}-reference")
        r = run(cmd + ["--out", references[name], "--threads", "2"])
        check(r.returncode == 0, f"{name}: uninterrupted sweep status {r.returncode}: {r.stderr[-800:]}")
        check(not os.path.exists(os.path.join(references[name], "runs.journal")), f"{name}: a finished sweep removes its journal")
        check(os.path.exists(os.path.join(references[name], "run_info.json")), f"{name}: run_info.json written")

    # SIGKILL mid-way, then --resume: 1 thread resumed on 2 (with a torn last line), 2 resumed on 1.
    # Under the sanitizers (--sanitized: every process several times slower) each journal path runs once: the
    # second peg-paper kill and the plain peg-matchup one are left to the Release suite (the sensing sweep below
    # kills peg-matchup there too).
    killed_then_resumed("peg-paper", sweeps["peg-paper"], os.path.join(work, "paper-kill-1"), references["peg-paper"], 1, 2, True)
    if not sanitized:
        killed_then_resumed("peg-paper", sweeps["peg-paper"], os.path.join(work, "paper-kill-2"), references["peg-paper"], 2, 1,
                            False)
        killed_then_resumed("peg-matchup", sweeps["peg-matchup"], os.path.join(work, "matchup-kill"),
                            references["peg-matchup"], 2, 1, True)
    killed_then_resumed("peg-generalize", sweeps["peg-generalize"], os.path.join(work, "generalize-kill"),
                        references["peg-generalize"], 1, 2, False)

    # Lidars, own maps and sight on, every replay written: runs read back from the journal keep their sensors'
    # readings, so a resumed sweep's replays hold the same lidar, map and sight layers, byte for byte.
    sensing = sweeps["peg-matchup"] + ["--html", "all"]
    for setting in ("pursuer.lidar.azimuth_rays=8", "pursuer.lidar.elevation_rays=2", "pursuer.map.enabled=true",
                    "pursuer.sight.enabled=true", "evader.sight.enabled=true"):
        sensing += ["--set", setting]
    references["sensing"] = os.path.join(work, "matchup-sensing-reference")
    r = run(sensing + ["--out", references["sensing"], "--threads", "2"])
    if check(r.returncode == 0, f"peg-matchup with sensing: status {r.returncode}: {r.stderr[-800:]}"):
        pages = [os.path.join(root, f) for root, _, files in os.walk(references["sensing"]) for f in files
                 if f.endswith(".html")]
        check(len(pages) == 64, f"peg-matchup with sensing: a replay per game, 4 pairings x 16 runs ({len(pages)})")
        with open(pages[0]) as f:
            page = f.read()
        check(all(f'"{layer}"' in page for layer in ("lidar", "map", "sight")),
              "peg-matchup with sensing: its replays hold the lidar, map and sight layers")
        killed_then_resumed("peg-matchup with sensing", sensing, os.path.join(work, "matchup-sensing-kill"),
                            references["sensing"], 2, 1, True)

    # SIGINT: stops within 2 s, status 130, says what it kept and how to resume; the printed command finishes it.
    out = os.path.join(work, "paper-int")
    cmd = sweeps["peg-paper"] + ["--out", out, "--threads", "2"]
    proc = start(cmd)
    if check(wait_for_runs(proc, out, 1), "peg-paper SIGINT: the sweep ended before a run was journaled"):
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        stopped = time.monotonic() - sent
        print(f"SIGINT: stopped in {stopped:.3f} s, status {proc.returncode}")
        check(stopped < 2.0, f"SIGINT stops within 2 s (took {stopped:.2f} s)")
        check(proc.returncode == 130, f"SIGINT exit status {proc.returncode}, expected 130: {err[-500:]}")
        kept = journal_runs(out)
        journal = os.path.join(out, "runs.journal")
        check(re.search(rf"kept {kept} of 16 runs in {re.escape(journal)}", err) is not None,
              f"SIGINT: says it kept {kept} of 16 runs in {journal}: {err[-500:]!r}")
        check(not os.path.exists(os.path.join(out, "runs.csv")), "SIGINT: no result file written")
        m = re.search(r"^resume with: (.*)$", err, re.M)
        if check(m is not None, f"SIGINT: prints the resume command: {err[-500:]!r}"):
            resume = shlex.split(m.group(1))
            check(resume == cmd + ["--resume"], f"the resume command is the same command plus --resume: {resume}")
            r = run(resume)
            check(r.returncode == 0, f"the printed resume command: status {r.returncode}: {r.stderr[-800:]}")
            same_results(references["peg-paper"], out, "peg-paper (SIGINT, resumed)")

    # SIGTERM: 143.
    out = os.path.join(work, "matchup-term")
    proc = start(sweeps["peg-matchup"] + ["--out", out, "--threads", "2"])
    if check(wait_for_runs(proc, out, 1), "peg-matchup SIGTERM: the sweep ended before a run was journaled"):
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=30)
        check(proc.returncode == 143, f"SIGTERM exit status {proc.returncode}, expected 143: {err[-500:]}")
        check("resume with:" in err, "SIGTERM: prints the resume command")

    # A journaled run whose pool opponents do not fit its training (edited by hand): status 2, naming the field.
    edited = os.path.join(work, "paper-edited")
    proc = start(sweeps["peg-paper"] + ["--out", edited, "--threads", "2"])
    if check(wait_for_runs(proc, edited, 1), "peg-paper (edited journal): the sweep ended before a run was journaled"):
        proc.kill()
        proc.wait()
        journal = os.path.join(edited, "runs.journal")
        with open(journal) as f:
            lines = f.read().splitlines()
        record = json.loads(lines[1])
        record["data"]["training_opponent"][0] = 99
        lines[1] = json.dumps(record)
        with open(journal, "w") as f:
            f.write("\n".join(lines) + "\n")
        r = run(sweeps["peg-paper"] + ["--out", edited, "--threads", "2", "--resume"])
        check(r.returncode == 2 and "training_opponent" in r.stderr and "runs.journal:2" in r.stderr,
              f"an edited journal's pool opponents: status {r.returncode}, {r.stderr[-300:]!r}")

    # peg-league stopped while it plays its games (every training run journaled): status 143, no result file;
    # --resume trains nothing again and plays the games, with the uninterrupted league's results. The games must
    # outlast the 0.5 s before the stop: 40 evaluation seeds in Release, 10 under the sanitizers (whose games are
    # several times slower; 40 took 33 s there against 8 s for 10).
    league = [os.path.join(bin_dir, "peg-league"), "--seed", "9", "--train-seeds", "2",
              "--eval-seeds", "10" if sanitized else "40", "--episodes", "5", "--no-plots", "--plain-progress"]
    league_ref, stopped = os.path.join(work, "league-reference"), os.path.join(work, "league-stopped")
    r = run(league + ["--out", league_ref, "--threads", "2"])
    check(r.returncode == 0, f"peg-league: status {r.returncode}: {r.stderr[-800:]}")
    proc = subprocess.Popen(league + ["--out", stopped, "--threads", "1"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    if check(wait_for_runs(proc, stopped, 4), f"peg-league ended before its 4 training runs were journaled: {proc.poll()}"):
        time.sleep(0.5)  # into the games
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=60)
        check(proc.returncode == 143, f"peg-league stopped in its games: status {proc.returncode}: {err[-500:]}")
        check(not os.path.exists(os.path.join(stopped, "games.csv")), "no result file after the stop")
        r = run(league + ["--out", stopped, "--threads", "2", "--resume"])
        check(r.returncode == 0 and "4 of 4 runs" in r.stderr, f"peg-league --resume: {r.stderr[-500:]}")
        if same_results(league_ref, stopped, "peg-league stopped in its games and resumed"):
            print("peg-league: stopped in its games, resumed identically")

    # Input errors, status 2, nothing run: a journal without --resume, another seed with --resume.
    base = sweeps["peg-matchup"] + ["--out", out, "--threads", "2"]
    journal = os.path.join(out, "runs.journal")
    size = os.path.getsize(journal) if os.path.exists(journal) else -1
    r = run(base)
    check(r.returncode == 2 and "--resume" in r.stderr and "runs.journal" in r.stderr,
          f"an existing journal without --resume: status {r.returncode}, {r.stderr[-300:]!r}")
    seed = [a if a != "7" else "8" for a in base]
    r = run(seed + ["--resume"])
    check(r.returncode == 2 and "runs.journal:1: setup.seed:" in r.stderr,
          f"--resume with another seed names setup.seed: status {r.returncode}, {r.stderr[-300:]!r}")
    check(size >= 0 and os.path.exists(journal) and os.path.getsize(journal) == size,
          "refused resumes leave the journal as it was")
    r = run(sweeps["peg-matchup"] + ["--out", os.path.join(work, "nothing"), "--resume"])
    check(r.returncode == 2 and "no journal" in r.stderr, f"--resume without a journal: status {r.returncode}, {r.stderr[-300:]!r}")
    check(not os.path.exists(os.path.join(work, "nothing")), "--resume without a journal writes nothing")

    print(f"{time.monotonic() - t0:.1f} s")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
