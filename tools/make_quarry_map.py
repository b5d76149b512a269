#!/usr/bin/env python3
"""Writes maps/quarry.yaml, a collision-rich map to start from: the valley terrain of maps/valley.yaml
(assets/valley.obj) with 520 dynamic bodies released over its slopes (rock blocks and slabs that fall, tumble
and settle on the slopes; a fifth of them pushable crates and balls that roll or slide further) and 120 scripted movers above the valley floor
(orbiting drones and cable cars running back and forth along the valley).

Usage: tools/make_quarry_map.py [OUT.yaml]
"""

import math
import pathlib
import random
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))

SEED = 20261201
SIZE = 35.0


def valley_height():
    """The terrain's height function, as tools/make_valley_mesh.py draws it (same seed, same bumps)."""
    import make_valley_mesh as mv
    rng = random.Random(mv.SEED)
    bumps = [(rng.uniform(0.5, 1.0) * mv.BUMP_HEIGHT, rng.uniform(0.08, 0.3), rng.uniform(0.08, 0.3),
              rng.uniform(0, 2 * math.pi), rng.uniform(0, 2 * math.pi)) for _ in range(mv.BUMPS)]

    def height(x, y):
        u = (x - mv.SIZE / 2) / (mv.SIZE / 2)
        z = mv.FLOOR + mv.SLOPE * u * u
        for a, kx, ky, px, py in bumps:
            z += a * math.sin(kx * x + px) * math.sin(ky * y + py)
        return z
    return height


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "maps" / "quarry.yaml"
    rng = random.Random(SEED)
    height = valley_height()
    lines = []
    # 520 bodies on a grid over both slopes, 1.2 m apart (so none starts inside another), each 0.9 m above
    # the terrain under it plus a little jitter, so they land at different times: blocks and slabs (four in
    # five) tumble and stay on the slope; the pushable balls and crates roll or slide further.
    bodies = 0
    xs = [2.0 + 1.2 * i for i in range(10)] + [SIZE - 2.0 - 1.2 * i for i in range(10)]
    ys = [1.6 + 1.2 * j for j in range(27)]
    for y in ys:
        for x in xs:
            if bodies == 520:
                break
            z = height(x, y) + 0.6 + 0.2 * rng.random()
            k = bodies % 5
            if k == 4:  # pushable: light crates and balls the agents can shove
                if bodies % 10 == 4:
                    lines.append(f"  - {{kind: box, size: [0.6, 0.6, 0.6], dynamic: {{position: [{x:.2f}, {y:.2f}, {z:.2f}], "
                                 f"mass: 15, friction: 0.9, restitution: 0.05, touch: pushable}}}}")
                else:
                    lines.append(f"  - {{kind: sphere, radius: 0.35, dynamic: {{position: [{x:.2f}, {y:.2f}, {z:.2f}], "
                                 f"mass: 8, friction: 0.6, rolling_friction: 0.4, restitution: 0.2, touch: pushable}}}}")
            elif k == 3:  # slabs, wider and flatter
                lines.append(f"  - {{kind: box, size: [0.9, 0.7, 0.3], rotation_deg: [0, 0, {rng.uniform(0, 90):.0f}], "
                             f"dynamic: {{position: [{x:.2f}, {y:.2f}, {z:.2f}], mass: 500, friction: 1.0, restitution: 0.0}}}}")
            else:  # blocks that land, tumble and stay on the slope (friction above the slopes' tangent)
                lines.append(f"  - {{kind: box, size: [0.7, 0.5, 0.45], rotation_deg: [0, 0, {rng.uniform(0, 90):.0f}], "
                             f"dynamic: {{position: [{x:.2f}, {y:.2f}, {z:.2f}], mass: 400, friction: 1.0, restitution: 0.0}}}}")
            bodies += 1
    # 120 scripted movers over the valley: 60 drones on level orbits at 11-17 m, 60 cable cars (boxes)
    # running back and forth along y at 10-16 m.
    for k in range(60):
        c = (rng.uniform(9, 26), rng.uniform(9, 26), rng.uniform(11, 17))
        lines.append(f"  - {{kind: sphere, radius: 0.3, orbit: {{center: [{c[0]:.2f}, {c[1]:.2f}, {c[2]:.2f}], "
                     f"radius: {rng.uniform(2, 7):.2f}, period: {rng.uniform(8, 30):.1f}, phase_deg: {rng.uniform(0, 360):.0f}}}}}")
    for k in range(60):
        x, z = rng.uniform(8, 27), rng.uniform(10, 16)
        lines.append(f"  - {{kind: box, size: [0.8, 1.2, 0.6], path: {{waypoints: [[{x:.2f}, 2, {z:.2f}], [{x:.2f}, 33, {z:.2f}]], "
                     f"speed: {rng.uniform(0.5, 2.0):.2f}, mode: back-and-forth}}}}")
    text = f"""# A quarry: the valley terrain of maps/valley.yaml with 520 rock blocks, slabs, crates and balls released over
# its slopes at t = 0 (they land, tumble and settle within seconds, the balls roll further; every fifth one is
# pushable: in push mode, mover_dynamics = push, agents shove it; otherwise it is solid like the rest) and 120
# scripted movers above the valley floor: 60 drones on level orbits and 60 cable cars running back and forth along the valley.
# Written by tools/make_quarry_map.py. Format and costs: docs/maps.md.
version: 1
name: quarry

arena:
  size: [35, 35, 20]
  faces_are_obstacles: {{floor: false, ceiling: true, walls: true}}

occupancy:
  resolution: 0.2
  max_distance: 5.0

# 30 keyframes a second (every eighth substep) keep the 520 bodies' timeline within its budget
# (docs/maps.md, "Moving obstacles").
physics:
  gravity: [0, 0, -9.81]
  rate_hz: 240
  keyframe_hz: 30
  faces_are_physical: true

terrain:
  - file: ../assets/valley.obj
    solid_below: true

movers:
{chr(10).join(lines)}

scenarios:
  - name: along        # down the valley, through the settling rocks and under the cable cars
    pursuer: {{position: [17.5, 3, 8]}}
    evader: {{position: [17.5, 32, 8]}}
  - name: high         # among the drones and cable cars
    pursuer: {{position: [5, 17.5, 18]}}
    evader: {{position: [30, 17.5, 18]}}
  - name: across       # from one slope to the other, over the falling rocks
    pursuer: {{position: [4, 17.5, 13]}}
    evader: {{position: [31, 17.5, 13]}}
"""
    out.write_text(text)
    print(f"{out}: {bodies} dynamic bodies, 120 scripted movers")


if __name__ == "__main__":
    main()
