#!/usr/bin/env python3
"""Writes maps/open_wall.yaml, maps/open_gap.yaml, maps/open_columns.yaml and maps/open_passage.yaml: four pursuers
against one evader around obstacles that hide it, after the four evaluation scenarios of OPEN (Chen et al.,
"Multi-UAV Pursuit-Evasion with Online Planning in Unknown Environments by Deep Reinforcement Learning",
github.com/thu-uav/Multi-UAV-pursuit-evasion: `scenario_flag` 'wall', 'narrow_gap', 'random' and 'passage').

OPEN flies Crazyflies in a round arena 0.9 m in radius and 1.2 m tall (cfg/task/HideAndSeek.yaml: arena_size
0.9, max_height 1.2) among upright cylinders 0.1 m in radius that stand the arena's full height, with the
pursuers starting on one side (x = 0.6-0.8 m) and the evader on the other (x = -0.8 m), 0.5 m up. Here the same
layouts are scaled by 10 in the plan, (x, y) -> (10 + 10 x, 10 + 10 y) m, into peg3d's box arena of
20 m x 20 m x 8 m with the usual agents (radius 0.25 m, capture within 1 m). The obstacles are peg3d's upright
cylinders, 8 m tall so that, as in OPEN, nobody flies over them; a wall is a row of them 0.6 m apart with a
radius of 0.5 m, so that neighbours overlap and no sight ray passes between them (a straight line crossing the
row meets the segment joining two neighbours' centres, which lies inside them). Openings are kept at least 2 m
wide: the agents' obstacle guard (stop_distance 0.8 m) must let them through. The columns of
open_columns.yaml are drawn with a fixed seed here and written out, so the map does not depend on the
loader's generator.

Only the standard library is used, so the output depends on nothing but the seed and this file.
Usage: tools/make_open_maps.py [OUT_DIR]   (default: maps/ in this script's repository)
"""

import math
import pathlib
import random
import sys

SIZE = (20.0, 20.0, 8.0)   # m, the arena
HEIGHT = 8.0               # m, every cylinder stands the arena's full height
WALL_RADIUS = 0.5          # m, the cylinders of walls and blocks
WALL_STEP = 0.6            # m between neighbouring centres (< 2 radii: they overlap)
COLUMNS_SEED = 20240701
COLUMNS = 14               # random columns
COLUMN_RADIUS = (0.5, 1.2)  # m
COLUMN_GAP = 1.8           # m, least distance between two columns' surfaces
COLUMN_MARGIN = 1.5        # m, least distance from a column's surface to the arena's walls
START_CLEARANCE = 1.0      # m, least distance from a start to any cylinder's surface

HEADER_COMMON = """\
# Written by tools/make_open_maps.py (do not edit by hand; change the script and rerun it). The arena is
# 20 m x 20 m x 8 m, OPEN's 0.9 m-radius, 1.2 m-tall round arena scaled by 10 in the plan into a box (corners
# are new hiding places; floor, ceiling and walls are obstacles); the cylinders stand its full height, as
# OPEN's do, so that nobody flies over them. Agents are peg3d's: radius 0.25 m, capture within 1 m, the
# evader slower than the pursuers (1.0 against 1.1 m/s; OPEN's cfg/task/HideAndSeek.yaml makes its prey 1.3
# times as fast as its drones). Format: docs/maps.md."""


def row(x0, y0, x1, y1):
    """Overlapping wall cylinders from (x0, y0) to (x1, y1), both ends included, at most WALL_STEP apart."""
    n = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / WALL_STEP))
    return [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n, WALL_RADIUS) for k in range(n + 1)]


def block(x0, y0, x1, y1):
    """A closed ring of overlapping cylinders whose outer surface spans [x0, x1] x [y0, y1]: a block, hollow inside
    (out of reach: the cylinders reach the ceiling)."""
    r = WALL_RADIUS
    a, b, c, d = (x0 + r, y0 + r), (x1 - r, y0 + r), (x1 - r, y1 - r), (x0 + r, y1 - r)
    ring = []
    for p, q in ((a, b), (b, c), (c, d), (d, a)):
        ring += row(*p, *q)[:-1]
    return ring


def random_columns(scenarios):
    """COLUMNS columns drawn in turn (radius, x, y), a draw that comes too close to a column placed before or to a
    start (in the plan) rejected."""
    starts = [(x, y) for s in scenarios for x, y, _ in s[2] + [s[3]]]
    rng = random.Random(COLUMNS_SEED)
    placed = []
    while len(placed) < COLUMNS:
        r = round(rng.uniform(*COLUMN_RADIUS), 2)
        m = r + COLUMN_MARGIN
        x, y = round(rng.uniform(m, SIZE[0] - m), 2), round(rng.uniform(m, SIZE[1] - m), 2)
        if all(math.hypot(x - u, y - v) - r - s >= COLUMN_GAP for u, v, s in placed) and \
                all(math.hypot(x - u, y - v) - r >= START_CLEARANCE + 0.5 for u, v in starts):
            placed.append((x, y, r))
    return placed


def agents(points):
    return "\n".join(f"      - {{position: [{x:g}, {y:g}, {z:g}]}}" for x, y, z in points)


def scenario(name, comment, pursuers, evader):
    return (f"  - name: {name}{' ' * max(1, 18 - len(name))}# {comment}\n    pursuers:\n{agents(pursuers)}\n"
            f"    evaders:\n{agents([evader])}\n")


def write(out_dir, name, header, cylinders, scenarios, obstacles_comment):
    for s in scenarios:  # every start keeps clear of every cylinder
        for x, y, z in s[2] + [s[3]]:
            for u, v, r in cylinders:
                gap = math.hypot(x - u, y - v) - r
                if gap < START_CLEARANCE:
                    raise SystemExit(f"{name}: scenario {s[0]}: start ({x}, {y}, {z}) is {gap:.2f} m "
                                     f"from cylinder ({u}, {v})")
    lines = [header, HEADER_COMMON, "version: 1", f"name: {name}", "", "arena:",
             f"  size: [{SIZE[0]:g}, {SIZE[1]:g}, {SIZE[2]:g}]",
             "  faces_are_obstacles: {floor: true, ceiling: true, walls: true}", "", "occupancy:", "  resolution: 0.2",
             "  max_distance: 5.0", "", f"# {obstacles_comment}", "obstacles:"]
    lines += [f"  - {{kind: cylinder, base: [{x:.2f}, {y:.2f}, 0], radius: {r:g}, height: {HEIGHT:g}}}"
              for x, y, r in cylinders]
    lines += ["", "scenarios:"]
    text = "\n".join(lines) + "\n" + "".join(scenario(*s) for s in scenarios)
    (out_dir / f"{name}.yaml").write_text(text)


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "maps"
    out.mkdir(parents=True, exist_ok=True)

    # OPEN 'wall': four cylinders at x = 0, y = +-0.15 and +-0.45 m, 0.1 m apart (a wall with three slits).
    write(out, "open_wall", """\
# OPEN's 'wall' scenario, four pursuers against one evader behind a wall. OPEN's wall is four cylinders of
# 0.1 m radius across the middle of its arena (y -0.45 to 0.45 m) with slits 0.1 m wide between them (1 m when
# scaled); here it is one solid wall along x = 10 m from y = 3 m to y = 17 m, 8 m tall, without slits, so that
# the evader behind it is out of sight and the pursuers must go round one of its ends (3 m wide passages along
# the arena's walls).""",
          row(10, 3.5, 10, 16.5),
          [("open", "OPEN's starts scaled: the pursuers east of the wall, the evader behind it",
            [(16, 14, 3.3), (16, 10, 3.3), (16, 6, 3.3), (18, 12, 3.3)], (2, 10, 3.3)),
           ("spread", "the pursuers spread over the east half and its heights, the evader behind the wall",
            [(17.5, 17.5, 2), (17.5, 2.5, 6), (13, 10, 4), (18, 10, 1.5)], (7.5, 11, 4.5)),
           ("ends", "two pursuers at each end of the wall, the evader close behind its middle",
            [(14, 1.5, 3), (12, 1.5, 5), (14, 18.5, 3), (12, 18.5, 5)], (8.5, 10, 3.3))],
          "The wall: overlapping cylinders along x = 10 m, y 3.5-16.5 m (their surfaces y 3-17 m).")

    # OPEN 'narrow_gap': cylinders at (+-0.3, +-0.3) and (0, 0.3): a square of posts with a narrow gap on each side.
    gap_lo, gap_hi = 12.0, 14.0
    write(out, "open_gap", """\
# OPEN's 'narrow_gap' scenario, four pursuers against one evader beyond a narrow gap. OPEN's is a square of five
# cylinders whose openings are a drone's width (0.1 m, 1 m when scaled); here it is one wall along x = 10 m
# across the whole arena, 8 m tall, with a single gap 2 m wide at y = 12-14 m (the narrowest the agents'
# obstacle guard lets them through): the only way from one side to the other.""",
          row(10, 0.3, 10, gap_lo - WALL_RADIUS) + row(10, gap_hi + WALL_RADIUS, 10, SIZE[1] - 0.3),
          [("open", "OPEN's starts, its three north of the posts moved east; the evader in line with the gap",
            [(12, 17, 3.3), (14, 17, 3.3), (16, 17, 3.3), (18, 12, 3.3)], (5, 12, 3.3)),
           ("spread", "the pursuers spread over the east side, the evader hiding by the wall west of it",
            [(17, 2.5, 2), (17, 17.5, 6), (13, 6, 4), (18.5, 10, 3)], (8, 5, 2.5)),
           ("at-the-gap", "the evader just west of the gap, the pursuers east and off its line",
            [(15, 3, 3), (15, 18, 3), (18, 6, 5), (12.5, 7, 2)], (8, 13, 4)),
           ("split", "two pursuers on each side, the evader in a corner west of the wall (seen by two)",
            [(14, 4, 3), (16, 16, 3), (5, 16, 4), (3, 10, 2)], (4, 3, 3))],
          f"The wall: overlapping cylinders along x = 10 m from y = 0.3 m to {SIZE[1] - 0.3:g} m but for the gap, "
          f"y {gap_lo:g}-{gap_hi:g} m.")

    # OPEN 'random': six fixed cylinders in an L (OPEN's random placements are drawn per episode).
    columns_scenarios = [
        ("open", "OPEN's starts scaled: the pursuers east, the evader west, beyond the columns",
         [(15, 10, 3.3), (15, 13, 3.3), (15, 7, 3.3), (18, 12, 3.3)], (2, 10, 3.3)),
        ("corners", "a pursuer in each corner at a different height, the evader among the columns",
         [(1.5, 1.5, 2), (18.5, 1.5, 4), (18.5, 18.5, 6), (1.5, 18.5, 3)], (10, 10, 4)),
        ("north-south", "the pursuers along the south wall, the evader by the north wall behind the columns",
         [(3, 1.5, 3), (8, 1.5, 5), (12, 1.5, 3), (17, 1.5, 5)], (11, 18.5, 3))]
    write(out, "open_columns", f"""\
# OPEN's 'random' scenario, four pursuers against one evader among columns. OPEN's evaluation uses six cylinders
# of 0.1 m radius in an L (its training draws up to five at random per episode); here {COLUMNS} columns of
# {COLUMN_RADIUS[0]:g}-{COLUMN_RADIUS[1]:g} m radius, 8 m tall, drawn once with seed {COLUMNS_SEED}: at least \
{COLUMN_GAP:g} m apart,
# {COLUMN_MARGIN:g} m from the arena's walls and {START_CLEARANCE + 0.5:g} m from every start in the plan. They are \
written out below,
# so the map does not depend on the loader's generator.""",
          random_columns(columns_scenarios), columns_scenarios,
          f"{COLUMNS} columns, seed {COLUMNS_SEED}.")

    # OPEN 'passage': rows of cylinders at x = +-0.2 m (y +-0.1 east, -0.3..0.3 west): a corridor 0.2 m wide.
    write(out, "open_passage", """\
# OPEN's 'passage' scenario, four pursuers against one evader at a narrow corridor between two blocks. OPEN's
# blocks are two short rows of cylinders (two east, four west) 0.2 m apart, the evader at the corridor's north
# mouth; here the blocks are 4 m x 11 m, each a closed ring of overlapping cylinders 8 m tall (hollow, out of
# reach), on either side of a corridor 2.5 m wide and 11 m long along y (x 8.75-11.25 m, y 4.5-15.5 m).""",
          block(4.75, 4.5, 8.75, 15.5) + block(11.25, 4.5, 15.25, 15.5),
          [("open", "OPEN's starts scaled: the evader at the corridor's north mouth, in sight of one",
            [(16.5, 10, 3.3), (18, 12, 3.3), (18, 8, 3.3), (17.5, 15, 3.3)], (10, 16.5, 4)),
           ("in-the-corridor", "the evader in the middle of the corridor, the pursuers spread outside the blocks",
            [(17.5, 10, 3), (2.5, 10, 5), (17.5, 2, 2), (2.5, 18, 6)], (10, 10, 3)),
           ("far-side", "the pursuers east of the blocks, the evader behind the west block",
            [(17.5, 6, 3), (17.5, 14, 5), (18.5, 10, 2), (17, 18.5, 4)], (2.5, 9, 3.5))],
          "Two blocks of overlapping cylinders, x 4.75-8.75 m and 11.25-15.25 m, y 4.5-15.5 m.")


if __name__ == "__main__":
    main()
