#!/usr/bin/env python3
"""Writes the maps of the scaling study in docs/performance.md: the paper's 35 m x 35 m x 20 m arena with one
thing grown at a time, for peg-throughput.

  obstacles_<n>.yaml    n = 10, 100, 1000 random spheres of radius 0.5 m
  terrain_<n>.yaml      the valley terrain at about n = 1k, 10k, 100k, 1M triangles (tools/make_valley_mesh.py)
  movers_<n>.yaml       n = 0, 1, 10, 100 spheres of radius 0.5 m on level orbits
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
    for n in (0, 1, 10, 100):
        movers = ""
        if n:
            movers = "physics:\n  rate_hz: 240\nmovers:\n"
            for k in range(n):
                # Level orbits at heights 2..18 m and radii 3..14 m round the centre, spread in phase.
                z = 2 + 16 * ((k * 7) % n) / max(n - 1, 1)
                r = 3 + 11 * ((k * 3) % n) / max(n - 1, 1)
                movers += (f"  - {{kind: sphere, radius: 0.5, orbit: {{center: [17.5, 17.5, {z:.3f}], radius: {r:.3f}, "
                           f"period: {20 + k % 7}, phase_deg: {(k * 137.5) % 360:.1f}}}}}\n")
        write(out, f"movers_{n}", HEAD.format(name=f"movers-{n}", faces=all_faces, resolution=0.2) + movers +
              ONE_ON_ONE.replace("[5, 30, 10]", "[1, 34, 1]").replace("[5, 5, 10]", "[1, 1, 1]")
              .replace("[30, 30, 10]", "[34, 34, 1]"))
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
