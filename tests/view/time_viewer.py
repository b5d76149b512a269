#!/usr/bin/env python3
"""Times a viewer file in headless Chromium (a measurement, never a test): how long until the page is ready,
its own load phases (pegView.timing), and the cost of a seek with its render, with and without the terrain.

usage: time_viewer.py FILE.html [--loads N] [--screenshot SHOT.png]
"""
import argparse
import json
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_viewer as cv  # noqa: E402  (the DevTools plumbing)


def seek_ms(page, count=20):
    start = time.time()
    for k in range(count):
        page.js(f"pegView.seek(pegView.duration * {k} / {count - 1})")
    return (time.time() - start) / count * 1000


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("html")
    ap.add_argument("--loads", type=int, default=3)
    ap.add_argument("--screenshot")
    a = ap.parse_args()
    import websocket
    profile = tempfile.mkdtemp(prefix="peg3d-chromium-")
    proc, port = cv.start_chromium(profile)
    try:
        page = cv.open_page(port, websocket)
        print(f"{a.html}: {os.path.getsize(a.html) / 1e6:.1f} MB")
        for _ in range(a.loads):
            ready = cv.load(page, a.html)
            with_terrain = seek_ms(page)
            page.js("pegView.setLayer('terrain', false)")
            without = seek_ms(page)
            page.js("pegView.setLayer('terrain', true)")
            timing = json.loads(page.js("JSON.stringify(pegView.timing || {})"))
            print(f"ready in {ready:.2f} s, {page.js('pegView.frames')} frames; seek+render {with_terrain:.0f} ms "
                  f"({without:.0f} ms without the terrain); page timing {timing}")
        problems = cv.console_problems(page, a.html)
        print("console and network:", "clean" if not problems else problems[:5])
        if a.screenshot:
            page.js("pegView.seek(pegView.duration / 2)")
            page.screenshot().save(a.screenshot)
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    main()
