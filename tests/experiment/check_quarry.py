#!/usr/bin/env python3
"""maps/quarry.yaml end to end: the collision-rich map users start from works with every program.

usage: check_quarry.py BIN_DIR SOURCE_DIR WORK_DIR [--sanitized]

1. peg-paper trains and evaluates on it, in the default mode and in push mode (mover_dynamics = push), and
   writes a replay viewer file.
2. peg-league trains a policy and plays it against the classic strategies on it.
3. The viewer file opens in headless Chromium (software WebGL) with its scene built, no console error and no
   network request; the time of a frame (seek, update of 640 movers, render) is measured and printed over 40
   instants of the episode: a measurement for docs/performance.md, never a pass/fail threshold. Skipped
   without Chromium or python3-websocket.
(peg-collide replays tests/collision/quarry-shared and quarry-push as ordinary collision cases.)

Under the sanitizers (--sanitized) the push mode and the viewer are left out. A push-mode game here steps 520
dynamic bodies (34 s in Release, about 5 times that sanitized) through code the quarry-push collision case and
the push tests run sanitized already; the viewer is a page checked in Chromium, which no sanitizer sees.

Exit status 0: all passed; 1: a check failed.
"""
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
sys.path.insert(0, os.path.join(HERE, "..", "view"))
from checks import check, failures  # noqa: E402


def run(cmd):
    print("$", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
    return r


def main():
    bin_dir, source, work = sys.argv[1:4]
    sanitized = "--sanitized" in sys.argv[4:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    quarry = os.path.join(source, "maps", "quarry.yaml")
    short = ["--set", "time_limit=8", "--threads", "2", "--plain-progress", "--no-plots"]

    # 1. peg-paper, both modes.
    for mode in ("shared",) if sanitized else ("shared", "push"):
        out = os.path.join(work, f"paper_{mode}")
        r = run([os.path.join(bin_dir, "peg-paper"), "--map", quarry, "--out", out, "--algorithms", "peg3d",
                 "--episodes", "2", "--repeats", "1", "--seed", "3", "--html", "along_*",
                 "--set", f"mover_dynamics={mode}"] + short)
        check(r.returncode == 0, f"peg-paper trains and evaluates on the quarry ({mode})")
        check(os.path.exists(os.path.join(out, "along_peg3d.html")), f"peg-paper writes the quarry's viewer ({mode})")
        check(any(f.endswith(".csv") for f in os.listdir(out)), f"peg-paper writes its result tables ({mode})")

    # 2. peg-league.
    out = os.path.join(work, "league")
    r = run([os.path.join(bin_dir, "peg-league"), "--map", quarry, "--out", out, "--algorithms", "peg3d",
             "--episodes", "2", "--train-seeds", "1", "--eval-seeds", "1", "--seed", "3"] + short)
    check(r.returncode == 0, "peg-league trains and plays on the quarry")
    check(len(os.listdir(out)) > 0, "peg-league writes its tables")
    if failures:
        return 1

    # 3. The viewer in Chromium.
    html = os.path.join(work, "paper_shared", "along_peg3d.html")
    if sanitized:
        print("viewer: left out under the sanitizers")
        return 0
    if shutil.which("chromium") is None:
        print("viewer: SKIPPED (no chromium)")
        return 0
    try:
        import websocket  # python3-websocket
        import check_viewer as cv
    except ImportError as e:
        print(f"viewer: SKIPPED ({e})")
        return 0
    profile = tempfile.mkdtemp(prefix="peg3d-chromium-")
    proc, port = cv.start_chromium(profile)
    try:
        page = cv.open_page(port, websocket)
        ready = cv.load(page, html)
        check(ready is not None, "the quarry's viewer builds its scene in Chromium")
        if ready is not None:
            frames = []
            for k in range(40):
                start = time.time()
                page.js(f"pegView.seek(pegView.duration * {k} / 39)")
                frames.append((time.time() - start) * 1000)
            print(f"viewer: {os.path.getsize(html) / 1e6:.1f} MB, ready in {ready:.2f} s; frame (seek, update, render) "
                  f"median {statistics.median(frames):.1f} ms, max {max(frames):.1f} ms over 40 instants")
        problems = cv.console_problems(page, html)
        check(not problems, "the quarry's viewer: no console error, no network request " + str(problems[:3]))
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
