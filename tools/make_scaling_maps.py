#!/usr/bin/env python3
"""Writes the maps of the scaling study in docs/performance.md: the paper's 35 m x 35 m x 20 m arena with one
thing grown at a time, for peg-throughput.

  obstacles_<n>.yaml    n = 10, 100, 1000 random spheres of radius 0.5 m
  terrain_<n>.yaml      the valley terrain at about n = 1k, 10k, 100k, 1M triangles (tools/make_valley_mesh.py)
  movers_<n>.yaml       n = 0, 1, 10, 100, 1000 spheres of radius 0.5 m on level orbits
  scripted_<n>.yaml     n = 10, 100, 1000 scripted movers over the whole arena, half on level orbits, half
                        spheres, cylinders and boxes on looping paths
  bodies_<n>.yaml       n = 10, 100, 1000 dynamic spheres resting on the floor, the agents 8 m above them
  falling_<n>.yaml      n = 10, 100, 1000 dynamic spheres and boxes dropped from 1-6 m onto the floor, where they
                        bounce and settle (the boulders of maps/rockfall.yaml, many times over)
  agents_<n>.yaml       n = 2, 4, 8, 16 agents, half pursuers, half evaders, 40 spheres
  resolution_<r>.yaml   maps/paper.yaml at r = 0.25, 0.2, 0.1 m

Usage: tools/make_scaling_maps.py OUT_DIR
"""

import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

HEAD = """version: 1
name: {name}
arena:
  size: [35, 35, 20]
  faces_are_obstacles: {faces}
occupancy:
  resolution: {resolution}
  max_distance: 5.0
"""

ONE_ON_ONE = """scenarios:
  - name: S1
    pursuer: {position: [5, 30, 10]}
    evader: {position: [5, 5, 10]}
  - name: S2
    pursuer: {position: [5, 5, 10]}
    evader: {position: [30, 30, 10]}
"""


def spheres(count, radius, seed=20240613):
    return f"""random_obstacles:
  - kind: sphere
    count: {count}
    radius: {radius}
    seed: {seed}
    clearance_from_starts: 1.5
    clearance_between: 0.1
"""


def orbit(k, n):
    """A sphere on a level orbit: heights 2..18 m and radii 3..14 m round the centre, spread in phase."""
    z = 2 + 16 * ((k * 7) % n) / max(n - 1, 1)
    r = 3 + 11 * ((k * 3) % n) / max(n - 1, 1)
    return (f"  - {{kind: sphere, radius: 0.5, orbit: {{center: [17.5, 17.5, {z:.3f}], radius: {r:.3f}, "
            f"period: {20 + k % 7}, phase_deg: {(k * 137.5) % 360:.1f}}}}}\n")


def path(k):
    """A sphere, cylinder or box looping over four waypoints of a rectangle somewhere in the arena at 1-2 m/s."""
    x0, y0, z = 2 + (k * 5.3) % 25, 2 + (k * 7.9) % 25, 2 + (k * 3.1) % 16
    w, h = 2 + k % 6, 2 + (k // 6) % 6
    points = f"[[{x0:.2f}, {y0:.2f}, {z:.2f}], [{x0 + w:.2f}, {y0:.2f}, {z:.2f}], [{x0 + w:.2f}, {y0 + h:.2f}, {z:.2f}], " \
             f"[{x0:.2f}, {y0 + h:.2f}, {z:.2f}]]"
    shape = ("kind: sphere, radius: 0.4", "kind: cylinder, radius: 0.3, height: 0.8", "kind: box, size: [0.6, 0.6, 0.6]")[k % 3]
    return f"  - {{{shape}, path: {{waypoints: {points}, speed: {1 + (k % 5) / 4:.2f}, mode: loop}}}}\n"


def grid(k, n):
    """Cell k of a square grid of n cells over the floor, 1.5 m from the walls."""
    side = math.ceil(math.sqrt(n))
    step = 32.0 / side
    return 1.5 + step * (k % side + 0.5), 1.5 + step * (k // side + 0.5)


def resting_ball(k, n):
    x, y = grid(k, n)
    return (f"  - {{kind: sphere, radius: 0.3, dynamic: {{position: [{x:.3f}, {y:.3f}, 0.3], mass: 20, friction: 0.8, "
            f"rolling_friction: 0.05, restitution: 0.1}}}}\n")


def falling_body(k, n):
    x, y = grid(k, n)
    z = 1 + (k * 0.37) % 5
    if k % 4 == 3:
        return (f"  - {{kind: box, size: [0.5, 0.4, 0.3], rotation_deg: [0, 0, {(k * 29) % 90}], dynamic: {{position: "
                f"[{x:.3f}, {y:.3f}, {z:.2f}], mass: 40, friction: 0.7, restitution: 0.05}}}}\n")
    return (f"  - {{kind: sphere, radius: 0.3, dynamic: {{position: [{x:.3f}, {y:.3f}, {z:.2f}], mass: 20, friction: 0.8, "
            f"rolling_friction: 0.05, restitution: 0.1}}}}\n")


def write(out, name, text):
    (out / f"{name}.yaml").write_text(text)


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    all_faces = "{floor: true, ceiling: true, walls: true}"
    for n in (10, 100, 1000):
        write(out, f"obstacles_{n}", HEAD.format(name=f"obstacles-{n}", faces=all_faces, resolution=0.2) +
              spheres(n, 0.5) + ONE_ON_ONE)
    # Valley grids of N x N vertices hold 2 (N - 1)^2 triangles.
    for label, n in (("1k", 23), ("10k", 72), ("100k", 225), ("1M", 708)):
        mesh = out / f"valley_{label}.obj"
        if not mesh.exists():
            subprocess.run([sys.executable, str(ROOT / "tools" / "make_valley_mesh.py"), str(mesh), str(n)], check=True)
        write(out, f"terrain_{label}",
              HEAD.format(name=f"terrain-{label}", faces="{floor: false, ceiling: true, walls: true}", resolution=0.2) +
              f"terrain:\n  - file: {mesh.name}\n    solid_below: true\n" + ONE_ON_ONE)
    corners = (ONE_ON_ONE.replace("[5, 30, 10]", "[1, 34, 1]").replace("[5, 5, 10]", "[1, 1, 1]")
               .replace("[30, 30, 10]", "[34, 34, 1]"))
    for n in (0, 1, 10, 100, 1000):
        movers = ""
        if n:
            movers = "physics:\n  rate_hz: 240\nmovers:\n" + "".join(orbit(k, n) for k in range(n))
        write(out, f"movers_{n}", HEAD.format(name=f"movers-{n}", faces=all_faces, resolution=0.2) + movers + corners)
    for n in (10, 100, 1000):
        movers = "physics:\n  rate_hz: 240\nmovers:\n"
        movers += "".join(orbit(k, n) if k % 2 == 0 else path(k) for k in range(n))
        write(out, f"scripted_{n}", HEAD.format(name=f"scripted-{n}", faces=all_faces, resolution=0.2) + movers + corners)
    high = ONE_ON_ONE.replace(", 10]}", ", 9]}")
    # A thousand bodies keep 30 keyframes a second (every eighth substep): every substep would need up to
    # 1.5 GiB, over the timeline's budget (docs/maps.md, "Moving obstacles").
    physics = "physics:\n  rate_hz: 240\n  keyframe_hz: 30\nmovers:\n"
    for n in (10, 100, 1000):
        write(out, f"bodies_{n}", HEAD.format(name=f"bodies-{n}", faces=all_faces, resolution=0.2) + physics +
              "".join(resting_ball(k, n) for k in range(n)) + high)
        write(out, f"falling_{n}", HEAD.format(name=f"falling-{n}", faces=all_faces, resolution=0.2) + physics +
              "".join(falling_body(k, n) for k in range(n)) + high)
    for n in (2, 4, 8, 16):
        half = n // 2
        pursuers = ", ".join(f"{{position: [3, {3 + 29 * k / max(half - 1, 1):.2f}, 10]}}" for k in range(half))
        evaders = ", ".join(f"{{position: [32, {3 + 29 * k / max(half - 1, 1):.2f}, 10]}}" for k in range(half))
        write(out, f"agents_{n}", HEAD.format(name=f"agents-{n}", faces=all_faces, resolution=0.2) + spheres(40, 1.0) +
              f"scenarios:\n  - name: T\n    pursuers: [{pursuers}]\n    evaders: [{evaders}]\n")
    paper = (ROOT / "maps" / "paper.yaml").read_text()
    for r in ("0.25", "0.2", "0.1"):
        text = paper.replace("resolution: 0.2 ", f"resolution: {r} ").replace("name: paper", f"name: paper-res-{r}")
        write(out, f"resolution_{r}", text)


if __name__ == "__main__":
    main()
