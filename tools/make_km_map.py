#!/usr/bin/env python3
"""Writes a 1 km x 1 km x 100 m terrain map (OUT/km.yaml and OUT/km_hills.obj): rolling hills up to about 30 m
(a height field of 101 x 101 vertices, 20 000 triangles, fixed seed), a pursuer and an evader 40 m apart in the
middle. For measuring own maps on an arena far larger than an episode explores (docs/performance.md, "Maps that grow
with what was seen"); the world's distance field is kept coarse (2 m) so that the arena builds in seconds.

Usage: tools/make_km_map.py OUT
"""

import math
import pathlib
import random
import sys

from make_valley_mesh import height_field  # this folder is on the path of a script run from it

SEED = 53
SIZE = 1000.0
N = 101


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    rng = random.Random(SEED)
    hills = [(rng.uniform(0, SIZE), rng.uniform(0, SIZE), rng.uniform(60, 200), rng.uniform(5, 15)) for _ in range(40)]

    def height(x, y):
        return 2.0 + sum(h * math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * r * r)) for cx, cy, r, h in hills)

    lines = height_field(lambda x, y: min(height(x, y), 30.0), SIZE, N)
    (out / "km_hills.obj").write_text("\n".join(lines) + "\n")
    mid = SIZE / 2
    z = min(height(mid, mid), 30.0) + 4.0
    (out / "km.yaml").write_text(f"""# 1 km x 1 km x 100 m of rolling hills (tools/make_km_map.py).
version: 1
name: km

arena:
  min: [0, 0, 0]
  size: [{SIZE:.0f}, {SIZE:.0f}, 100]
  faces_are_obstacles: {{floor: false, ceiling: true, walls: true}}

occupancy:
  resolution: 2.0
  max_distance: 10.0

terrain:
  - file: km_hills.obj
    solid_below: true

scenarios:
  - name: middle
    pursuer: {{position: [{mid - 20:.1f}, {mid:.1f}, {z:.1f}]}}
    evader: {{position: [{mid + 20:.1f}, {mid:.1f}, {z:.1f}]}}
""")


if __name__ == "__main__":
    main()
