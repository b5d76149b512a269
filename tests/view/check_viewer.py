#!/usr/bin/env python3
"""The replay viewer in a real browser (headless Chromium, software WebGL), driven over the DevTools protocol.

usage: check_viewer.py BIN_DIR SOURCE_DIR WORK_DIR

1. Writes viewer files the three ways users do: peg-paper --html on tests/data/viewer/scene.yaml (terrain,
   spheres, a cylinder, an orbiting mover), peg-view from the trajectory file it wrote, and
   peg-collide run --html on a collision case.
2. Opens each in Chromium and checks: the page builds its scene (window.pegView.ready), the JavaScript
   console holds no error and no exception, and the page makes no network request.
3. On the peg-paper file, from the pixels of screenshots at two instants: hiding the obstacles, the terrain,
   the trails or the movers changes the picture (so each is drawn), and the agents' pixels lie elsewhere at
   the second instant (so they moved); the agent panel labels the fuzzy inputs from the library's table and
   shows their values; a key steps a frame, play advances, the URL fragment seeks, and the pair, agent and
   follow selectors work, all without a console error. The screenshots stay in WORK_DIR to look at.
4. On a sensing game's file (peg-matchup --html on maps/forest.yaml, lidars and own maps): the selected agent's
   map shows, at frames reached forwards and backwards, exactly the cells the replay's flips make occupied, its
   rays are drawn, and hiding the sensing layer changes the picture.
5. On a limited-sight game's file: the sight layer is drawn while the pursuer sees its opponent and while it does not.
6. On a depth camera's file (peg-matchup --html, the pursuer's camera feeding its own map): the images layer shows
   the selected agent's image of each frame, pixel for pixel as the replay's depths say, the map its images
   built is shown, and hiding the layer changes the picture.

Exit status 0: all passed; 77: skipped (no Chromium, or no python3-websocket); 1: a check failed.
"""
import base64
import glob
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import checks  # noqa: E402
from checks import failures, verdict  # noqa: E402

SKIP = 77
# Chromium's software GL reports reading pixels back (each screenshot) as a "performance" driver message.
HARMLESS = ("GPU stall due to ReadPixels",)


def check(ok, what):
    return checks.check(ok, what, verbose=True)


def run(cmd, **kw):
    r = checks.run(cmd, timeout=600, **kw)
    if r.returncode != 0:
        print(f"command failed ({r.returncode}): {' '.join(cmd)}\n{r.stdout[-2000:]}\n{r.stderr[-2000:]}")
    return r


class Page:
    """One Chromium tab over the DevTools protocol: commands, and the events that arrived meanwhile."""

    def __init__(self, ws_url, websocket):
        self.ws = websocket.create_connection(ws_url, timeout=60, suppress_origin=True)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        my_id = self.next_id
        self.ws.send(json.dumps({"id": my_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == my_id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            if "method" in msg:
                self.events.append(msg)

    def js(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expression}: {r['exceptionDetails'].get('exception', {}).get('description')}")
        return r["result"].get("value")

    def screenshot(self):
        from PIL import Image
        data = self.call("Page.captureScreenshot", format="png")["data"]
        return Image.open(io.BytesIO(base64.b64decode(data))).convert("RGB")


def start_chromium(profile):
    exe = shutil.which("chromium")
    cmd = [exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader", "--enable-unsafe-swiftshader",
           "--window-size=1280,800", "--no-first-run", "--no-default-browser-check", "--disable-extensions",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           f"--user-data-dir={profile}", "--remote-debugging-port=0", "about:blank"]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    port_file = os.path.join(profile, "DevToolsActivePort")
    deadline = time.time() + 60
    while time.time() < deadline:
        if os.path.exists(port_file):
            lines = open(port_file).read().split()
            if lines:
                return proc, int(lines[0])
        time.sleep(0.1)
    proc.kill()
    raise RuntimeError("Chromium did not open its DevTools port within 60 s")


def open_page(port, websocket):
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30) as r:
        targets = [t for t in json.load(r) if t.get("type") == "page"]
    page = Page(targets[0]["webSocketDebuggerUrl"], websocket)
    for domain in ("Runtime", "Log", "Network", "Page"):
        page.call(f"{domain}.enable")
    return page


def load(page, html):
    """Navigates to the file and waits for the viewer; returns the load time in seconds."""
    page.events.clear()
    start = time.time()
    page.call("Page.navigate", url="file://" + os.path.abspath(html))
    deadline = start + 120
    while time.time() < deadline:
        try:
            if page.js("!!(window.pegView && window.pegView.ready)"):
                return time.time() - start
        except RuntimeError:
            pass  # the page is between documents
        time.sleep(0.1)
    return None


def console_problems(page, html):
    """Errors, exceptions and warnings of the page's console and log; requests other than the page itself."""
    problems = []
    own = "file://" + os.path.abspath(html)
    for e in page.events:
        m, p = e["method"], e.get("params", {})
        if m == "Runtime.exceptionThrown":
            problems.append("exception: " + json.dumps(p.get("exceptionDetails", {}))[:300])
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert", "warning"):
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
            if not any(h in text for h in HARMLESS):
                problems.append(f"console.{p['type']}: {text[:300]}")
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") in ("error", "warning"):
            text = p["entry"].get("text", "")
            if not any(h in text for h in HARMLESS):
                problems.append(f"log {p['entry']['level']}: {text[:300]}")
        elif m == "Network.requestWillBeSent":
            url = p.get("request", {}).get("url", "")
            if url != own:
                problems.append(f"network request: {url[:200]}")
    return problems


def changed_pixels(a, b):
    import numpy as np
    d = np.abs(np.asarray(a, dtype=np.int16) - np.asarray(b, dtype=np.int16)).sum(axis=2)
    return d > 24


def hidden_layer_pixels(page, layer, full):
    """How many pixels of the screenshot `full` change when `layer` is hidden (it is shown again after)."""
    page.js(f"pegView.setLayer('{layer}', false)")
    without = page.screenshot()
    page.js(f"pegView.setLayer('{layer}', true)")
    return int(changed_pixels(full, without).sum())


def centroid(mask):
    import numpy as np
    ys, xs = np.nonzero(mask)
    return (float(xs.mean()), float(ys.mean())) if len(xs) else None


def occupied_cells(agent, frame):
    """Agent's own-map cells occupied at `frame`, from the replay's flips (independently of the viewer)."""
    import numpy as np
    m = agent["map"]
    frames = np.frombuffer(base64.b64decode(m["flip_frames_u32"]), dtype="<u4")
    centres = np.frombuffer(base64.b64decode(m["flip_centres_f32"]), dtype="<f4").reshape(-1, 3)
    occupied = np.frombuffer(base64.b64decode(m["flip_occupied_u8"]), dtype=np.uint8)
    cells = set()
    for k in range(len(frames)):
        if frames[k] > frame:
            break
        key = tuple(int(np.floor(float(c) / m["resolution"])) for c in centres[k])  # centres lie mid-cell
        (cells.add if occupied[k] else cells.discard)(key)
    return len(cells)


def check_sensing(page, html, work):
    """4. The sensing layer: the selected agent's rays and its own map as the replay's flips make it, at frames
    reached forwards and backwards, for each agent; drawn (pixels change when the layer is hidden)."""
    import numpy as np
    if not check(load(page, html) is not None, "the sensing game's viewer is ready"):
        return
    replay = json.loads(page.js("document.getElementById('peg-replay').textContent"))
    times = np.frombuffer(base64.b64decode(replay["times_f64"]), dtype="<f8")
    n = len(times)
    check(all("lidar" in a and "map" in a for a in replay["agents"]), "every agent's lidar and map are in the replay")
    for agent in (0, 1):
        page.js(f"(function () {{ var s = document.getElementById('peg-agent'); s.value = '{agent}';"
                " s.dispatchEvent(new Event('change')); })()")
        rays = replay["agents"][agent]["lidar"]["rays"]
        active = np.frombuffer(base64.b64decode(replay["agents"][agent]["track"]["active_u8"]), dtype=np.uint8)
        for f in (n - 1, n // 3, 2 * n // 3, 0, n - 1):
            page.js(f"pegView.seek({float(times[f])!r})")
            shown = page.js("pegView.sensing")
            want = occupied_cells(replay["agents"][agent], f)
            check(shown["agent"] == agent and shown["cells"] == want and want > 0,
                  f"agent {agent}, frame {f}: {shown['cells']} map cells shown, the flips make {want}")
            check(page.js("pegView.frame") == f and shown["rays"] == (rays if active[f] else 0),
                  f"agent {agent}, frame {f}: {shown['rays']} of {rays} rays drawn (active: {active[f]})")
    page.js("(function () { var s = document.getElementById('peg-agent'); s.value = '0';"
            " s.dispatchEvent(new Event('change')); })()")
    page.js(f"pegView.seek({float(times[n // 2])!r})")
    check(page.js("pegView.sensing").get("rays") == replay["agents"][0]["lidar"]["rays"], "the pursuer's rays are drawn mid-game")
    full = page.screenshot()
    full.save(os.path.join(work, "viewer_sensing.png"))
    changed = hidden_layer_pixels(page, "sensing", full)
    check(changed > 100, f"the rays and the map are drawn ({changed} pixels change when they are hidden)")
    problems = console_problems(page, html)
    check(not problems, "no console error while driving the sensing layer" + ("" if not problems else ": " + "; ".join(problems[:5])))


def check_sight(page, html, work):
    """5. The sight layer: lines of sight, fields of view and ghosts are drawn (pixels change when the layer is
    hidden), at an instant the pursuer sees the evader and at one it does not (read from the replay's data)."""
    import numpy as np
    if not check(load(page, html) is not None, "the limited-sight game's viewer is ready"):
        return
    check(page.js("Object.keys(pegView.layers).indexOf('sight') >= 0"), "the sight layer is listed")
    replay = json.loads(page.js("document.getElementById('peg-replay').textContent"))
    times = np.frombuffer(base64.b64decode(replay["times_f64"]), dtype="<f8")
    visible = np.frombuffer(base64.b64decode(replay["agents"][0]["sight"]["visible_u8"]), dtype=np.uint8)
    for label, frames in (("seen", np.nonzero(visible[1:])[0]), ("hidden", np.nonzero(visible[1:] == 0)[0])):
        if not check(len(frames) > 0, f"the pursuer's opponent is {label} at some frame"):
            continue
        f = int(frames[len(frames) // 2]) + 1
        page.js(f"pegView.seek({float(times[f])!r})")
        full = page.screenshot()
        full.save(os.path.join(work, f"viewer_sight_{label}.png"))
        n = hidden_layer_pixels(page, "sight", full)
        check(n > 30, f"frame {f}: the sight layer is drawn while the opponent is {label} ({n} pixels)")
    problems = console_problems(page, html)
    check(not problems, "no console error while driving the sight layer" + ("" if not problems else ": " + "; ".join(problems[:5])))


def check_camera(page, html, work):
    """6. The images layer: the pursuer's depth image at frames reached forwards and backwards is the one the replay
    holds for that frame, pixel for pixel (near bright, far dark, no echo dark blue); its map shows; the evader, without
    a camera, shows none; hiding the layer changes the picture."""
    import numpy as np
    from PIL import Image
    if not check(load(page, html) is not None, "the depth camera game's viewer is ready"):
        return
    replay = json.loads(page.js("document.getElementById('peg-replay').textContent"))
    times = np.frombuffer(base64.b64decode(replay["times_f64"]), dtype="<f8")
    n = len(times)
    image = replay["agents"][0]["camera"]["image"]
    rows, columns = image["rows"], image["columns"]
    values = np.frombuffer(base64.b64decode(image["values_f32"]), dtype="<f4").reshape(n, rows, columns)
    echo = np.frombuffer(base64.b64decode(image["echo_u8"]), dtype=np.uint8).reshape(n, rows, columns)
    taken = np.frombuffer(base64.b64decode(image["scan_frame_u32"]), dtype="<u4")
    check("camera" not in replay["agents"][1], "the evader has no camera layer")
    for f in (n - 1, n // 3, 2 * n // 3, 0):
        page.js(f"pegView.seek({float(times[f])!r})")
        shown = page.js("pegView.sensing")
        want = {"agent": 0, "sensor": "camera", "rows": rows, "columns": columns, "frame": int(taken[f])}
        check(shown["image"] == want, f"frame {f}: the image shown is {shown['image']}, the replay's is {want}")
        png = page.js("document.getElementById('peg-image-canvas').toDataURL('image/png')")
        rgba = np.asarray(Image.open(io.BytesIO(base64.b64decode(png.split(",", 1)[1]))).convert("RGBA"), dtype=np.int64)
        gray = np.round(255 * (1 - np.clip((values[f] - image["low"]) / (image["high"] - image["low"]), 0, 1)))
        want_rgb = np.where(echo[f][..., None] == 0, np.array([18, 26, 58]), np.repeat(gray[..., None], 3, axis=2))
        bad = int((np.abs(rgba[..., :3] - want_rgb) > 1).any(axis=2).sum())
        check(bad == 0 and echo[f].sum() > 0, f"frame {f}: every pixel as the replay's depths say ({bad} differ, "
              f"{int(echo[f].sum())} echoes of {rows * columns})")
        check(shown["cells"] == occupied_cells(replay["agents"][0], f) and shown["cells"] > 0,
              f"frame {f}: the map the images built shows {shown['cells']} cells")
    page.js(f"pegView.seek({float(times[n // 2])!r})")
    full = page.screenshot()
    full.save(os.path.join(work, "viewer_camera.png"))
    changed = hidden_layer_pixels(page, "images", full)
    check(changed > 1000, f"the image is drawn ({changed} pixels change when the layer is hidden)")
    page.js("(function () { var s = document.getElementById('peg-agent'); s.value = '1';"
            " s.dispatchEvent(new Event('change')); })()")
    check(page.js("pegView.sensing").get("image") is None and page.js("document.getElementById('peg-image').hidden"),
          "an agent without a camera shows no image")
    problems = console_problems(page, html)
    check(not problems, "no console error while driving the images layer" + ("" if not problems else ": " + "; ".join(problems[:5])))


def main():
    bin_dir, source, work = sys.argv[1:4]
    if shutil.which("chromium") is None:
        print("SKIPPED: chromium is not installed (tools/test.sh installs it)")
        return SKIP
    try:
        import websocket  # python3-websocket
        import numpy  # noqa: F401
        from PIL import Image  # noqa: F401
    except ImportError as e:
        print(f"SKIPPED: {e} (tools/test.sh installs python3-websocket, python3-numpy, python3-pil)")
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scene = os.path.join(source, "tests", "data", "viewer", "scene.yaml")

    # 1. Viewer files, three ways.
    paper_out = os.path.join(work, "paper")
    r = run([os.path.join(bin_dir, "peg-paper"), "--map", scene, "--out", paper_out, "--algorithms", "peg3d",
             "--episodes", "3", "--repeats", "1", "--seed", "5", "--no-plots", "--no-cache", "--html", "across_*",
             "--plain-progress"])
    paper_html = os.path.join(paper_out, "across_peg3d.html")
    check(r.returncode == 0 and os.path.exists(paper_html), "peg-paper --html writes across_peg3d.html")
    check(f"replay viewer: {paper_html}" in r.stdout, "peg-paper names the viewer file in its summary")
    view_html = os.path.join(work, "from_csv.html")
    r = run([os.path.join(bin_dir, "peg-view"), "--map", scene, "--trajectory",
             os.path.join(paper_out, "trajectories", "across_peg3d.csv"), "--out", view_html, "--no-cache"])
    check(r.returncode == 0 and os.path.exists(view_html), "peg-view writes a viewer from a trajectory file")
    case_dir = os.path.join(work, "cases")
    r = run([os.path.join(bin_dir, "peg-collide"), "--no-cache", "run",
             os.path.join(source, "tests", "collision", "mover-crosses-path"), "--html", case_dir])
    case_html = os.path.join(case_dir, "mover-crosses-path.html")
    check(r.returncode == 0 and os.path.exists(case_html), "peg-collide run --html writes the case's viewer")
    sensing_out = os.path.join(work, "sensing")
    sets = ["--set", "time_limit=25"]
    for role in ("pursuer", "evader"):
        sets += ["--set", f"{role}.lidar.azimuth_rays=24", "--set", f"{role}.lidar.elevation_rays=3",
                 "--set", f"{role}.lidar.elevation_fov=40", "--set", f"{role}.map.enabled=true"]
    r = run([os.path.join(bin_dir, "peg-matchup"), "--map", os.path.join(source, "maps", "forest.yaml"),
             "--out", sensing_out, "--pursuers", "pn", "--evaders", "flee", "--repeats", "1", "--no-cache",
             "--html", "F1_r0_pn_vs_flee", "--plain-progress", *sets])
    sensing_html = os.path.join(sensing_out, "F1_r0_pn_vs_flee.html")
    check(r.returncode == 0 and os.path.exists(sensing_html), "peg-matchup --html writes a sensing game's viewer")
    sight_out = os.path.join(work, "sight")
    r = run([os.path.join(bin_dir, "peg-matchup"), "--map", os.path.join(source, "maps", "town.yaml"),
             "--out", sight_out, "--pursuers", "search", "--evaders", "hide", "--repeats", "1", "--no-cache",
             "--html", "corner_r0_search_vs_hide", "--plain-progress", "--set", "time_limit=40",
             "--set", "pursuer.sight.enabled=true", "--set", "pursuer.sight.fov=120", "--set", "evader.sight.enabled=true"])
    sight_html = os.path.join(sight_out, "corner_r0_search_vs_hide.html")
    check(r.returncode == 0 and os.path.exists(sight_html), "peg-matchup --html writes a limited-sight game's viewer")
    camera_out = os.path.join(work, "camera")
    r = run([os.path.join(bin_dir, "peg-matchup"), "--map", os.path.join(source, "maps", "forest.yaml"),
             "--out", camera_out, "--pursuers", "pn", "--evaders", "flee", "--repeats", "1", "--no-cache",
             "--html", "F1_r0_pn_vs_flee", "--plain-progress", "--set", "time_limit=20",
             "--set", "pursuer.camera.width=32", "--set", "pursuer.camera.height=24", "--set", "pursuer.camera.range=12",
             "--set", "pursuer.map.enabled=true"])
    camera_html = os.path.join(camera_out, "F1_r0_pn_vs_flee.html")
    check(r.returncode == 0 and os.path.exists(camera_html), "peg-matchup --html writes a depth camera game's viewer")
    if failures:
        return 1

    profile = tempfile.mkdtemp(prefix="peg3d-chromium-")
    proc, port = start_chromium(profile)
    try:
        page = open_page(port, websocket)
        # 2. Every file opens offline, quietly.
        for html in (paper_html, view_html, case_html, sensing_html, sight_html, camera_html):
            name = os.path.basename(html)
            seconds = load(page, html)
            if not check(seconds is not None, f"{name}: the viewer is ready ({os.path.getsize(html) / 1e6:.1f} MB)"):
                continue
            print(f"     loaded in {seconds:.2f} s")
            page.js("pegView.seek(pegView.duration / 2)")
            problems = console_problems(page, html)
            check(not problems, f"{name}: no console error, no exception, no network request" +
                  ("" if not problems else ": " + "; ".join(problems[:5])))

        # 3. The pixels of the peg-paper file.
        if load(page, paper_html) is None:
            return 1
        duration = page.js("pegView.duration")
        frames = page.js("pegView.frames")
        check(frames > 10, f"the episode has {frames} frames over {duration:.1f} s")
        shots = {}
        agents_at = {}
        for label, t in (("early", 0.2 * duration), ("late", 0.8 * duration)):
            page.js(f"pegView.seek({t})")
            full = page.screenshot()
            full.save(os.path.join(work, f"viewer_{label}.png"))
            shots[label] = full
            page.js("pegView.setLayer('agents', false)")
            without = page.screenshot()
            page.js("pegView.setLayer('agents', true)")
            agents_at[label] = changed_pixels(full, without)
        page.js(f"pegView.seek({0.8 * duration})")
        for layer in ("obstacles", "terrain", "trails", "movers"):
            n = hidden_layer_pixels(page, layer, shots["late"])
            check(n > 100, f"the {layer} are drawn ({n} pixels change when they are hidden)")
        a, b = centroid(agents_at["early"]), centroid(agents_at["late"])
        if check(a is not None and b is not None, "the agents are drawn at both instants"):
            moved = ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5
            check(moved > 10, f"the agents moved between the instants ({moved:.0f} pixels)")
        n = int(changed_pixels(shots["early"], shots["late"]).sum())
        check(n > 500, f"the two instants look different ({n} pixels)")
        # The agent panel labels the fuzzy inputs from the library's table (game::kObservationEntries), and
        # shows a number for each.
        rows = page.js("Array.from(document.querySelectorAll('#peg-agent-info tr')).map(function (r) {"
                       " return Array.from(r.children).map(function (c) { return c.textContent; }); })")
        inputs = {r[0]: r for r in rows if len(r) == 3}
        for label, unit in (("d to opponent", "m"), ("opponent azimuth error", "rad"), ("obstacle elevation error", "rad")):
            row = inputs.get(label)
            check(row is not None and row[2] == unit and row[1] not in ("", "\u2013"),
                  f"the agent panel shows '{label}' in {unit}: {row}")
        # The controls: a key steps one frame, play advances, the URL fragment seeks, the selectors switch
        # the pair, the agent and the followed agent (each wired through its own part of the viewer).
        page.js("pegView.seek(pegView.duration / 4)")
        before = page.js("pegView.frame")
        page.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'ArrowRight'}))")
        check(page.js("pegView.frame") == before + 1, "the right-arrow key steps one frame")
        page.js("document.getElementById('peg-play').click()")
        time.sleep(0.6)
        page.js("document.getElementById('peg-play').click()")
        check(page.js("pegView.frame") > before + 1, "play advances the replay")
        page.js("location.hash = '#t=' + (pegView.duration / 3)")
        time.sleep(0.3)
        t = page.js("pegView.time")
        check(t <= duration / 3 + 1e-9 and t > duration / 3 - 0.2, f"the URL fragment seeks to a third ({t:.2f} s)")
        for select, value in (("peg-pair", "0"), ("peg-agent", "1"), ("peg-follow", "0")):
            page.js(f"(function () {{ var s = document.getElementById('{select}'); s.value = '{value}';"
                    " s.dispatchEvent(new Event('change')); })()")
        page.js("pegView.seek(pegView.duration / 2)")
        check(page.js("document.getElementById('peg-agent-info').textContent.indexOf('fuzzy inputs') >= 0"),
              "the agent panel is rebuilt for the agent chosen")
        problems = console_problems(page, paper_html)
        check(not problems, "no console error or network request while driving the page" +
              ("" if not problems else ": " + "; ".join(problems[:5])))
        check_sensing(page, sensing_html, work)
        check_sight(page, sight_html, work)
        check_camera(page, camera_html, work)
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
    print(f"screenshots: {os.path.join(work, 'viewer_early.png')}, {os.path.join(work, 'viewer_late.png')}")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
