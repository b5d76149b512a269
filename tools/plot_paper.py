#!/usr/bin/python3
"""Draws the paper's figures from the result folder of the peg-paper experiment (formats: docs/results.md).

Usage: tools/plot_paper.py RESULTS_DIR [--only NAME ...]

Writes into RESULTS_DIR (each PNG saved to a temporary name, then renamed):
  trajectories.png  Fig. 4: per scenario, the evaluation episode of repeat 0 of every algorithm in 3D
                    (trajectories/<scenario>_<algorithm>.csv, map.json; runs.csv for the outcome if present)
  comparison.png    Fig. 5: mean pursuer path length and capture time per scenario and algorithm with 95%
                    intervals, capture counts and paired p-values (summary.json)
  learning.png      capture rate and episode time over the co-learning training episodes (opponent-pool
                    episodes are left out), mean +- 1 standard error over repeats (learning_curves.csv)
  apollonius.png    Fig. 2: the generalized Apollonius surfaces for several speed ratios a and the pursuer's
                    motion cone (apollonius.json)

--only NAME ... draws only the named figures (trajectories, comparison, learning, apollonius). Exit status: 0 when
every requested figure was written, 2 (with "error: ..." on stderr) when RESULTS_DIR or an input file a figure
needs is missing or malformed; figures whose inputs are fine are still written.

Runs under Debian's /usr/bin/python3 with python3-numpy and python3-matplotlib (Agg backend, no display).
"""

import argparse
import csv
import json
import math
import os
import re
import sys
import tempfile
import warnings
import zlib

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.colors  # noqa: E402
import matplotlib.ticker  # noqa: E402
import matplotlib.transforms  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

FIGURES = ("trajectories", "comparison", "learning", "apollonius")
KNOWN_ALGORITHMS = ("peg3d", "paper", "baseline")
ALGORITHM_COLORS = {"peg3d": "#1f77b4", "paper": "#ff7f0e", "baseline": "#2ca02c"}
EXTRA_COLORS = ("#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
MOVING_AVERAGE_EPISODES = 10
DPI = 130
SAVE_METADATA = {"Software": None}


class InputError(Exception):
    """A missing or malformed input file; the message names the file."""


# ----------------------------------------------------------------------------------------------------------------
# Reading


def natural_key(name):
    """S2 before S10."""
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", name)]


def order_algorithms(names):
    names = set(names)
    known = [a for a in KNOWN_ALGORITHMS if a in names]
    return known + sorted(names - set(known), key=natural_key)


def algorithm_color(name):
    """A fixed colour per algorithm name (the same in every figure and every run)."""
    if name in ALGORITHM_COLORS:
        return ALGORITHM_COLORS[name]
    return EXTRA_COLORS[zlib.crc32(name.encode("utf-8")) % len(EXTRA_COLORS)]


def read_json(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: missing")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise InputError(f"{path}: malformed JSON ({e})") from None


def read_csv(path, required):
    """Returns (column index by name, rows as lists of strings); every row has one field per column."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: missing")
    try:
        with open(path, encoding="utf-8", newline="") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None:
                raise InputError(f"{path}: empty (no header line)")
            rows = list(reader)
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: unreadable CSV ({e})") from None
    index = {name: i for i, name in enumerate(header)}
    missing = [c for c in required if c not in index]
    if missing:
        raise InputError(f"{path}: missing column(s) {', '.join(missing)}")
    for line, row in enumerate(rows, start=2):
        if len(row) != len(header):
            if not row:  # a blank line
                raise InputError(f"{path}:{line}: blank line")
            raise InputError(f"{path}:{line}: {len(row)} fields, the header has {len(header)}")
    return index, rows


def parse_float(text, where):
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise InputError(f"{where}: '{text}' is not a number") from None


def parse_int(text, where):
    try:
        return int(text)
    except ValueError:
        raise InputError(f"{where}: '{text}' is not an integer") from None


def parse_flag(text, where):
    lowered = text.strip().lower()
    if lowered in ("1", "true"):
        return 1.0
    if lowered in ("0", "false"):
        return 0.0
    if lowered in ("", "nan"):
        return math.nan
    raise InputError(f"{where}: '{text}' is not 0/1")


def json_number(value, where):
    """A JSON number, or nan for null (nlohmann writes NaN as null)."""
    if value is None:
        return math.nan
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{where}: expected a number, got {json.dumps(value)}")
    return float(value)


def json_vec3(value, where):
    if not isinstance(value, list) or len(value) != 3:
        raise InputError(f"{where}: expected [x, y, z], got {json.dumps(value)}")
    v = np.array([json_number(x, where) for x in value], dtype=float)
    if not np.all(np.isfinite(v)):
        raise InputError(f"{where}: non-finite coordinate")
    return v


def json_object(value, where):
    if not isinstance(value, dict):
        raise InputError(f"{where}: expected an object")
    return value


def json_list(value, where):
    if value is None:
        return []
    if not isinstance(value, list):
        raise InputError(f"{where}: expected a list")
    return value


def read_map(results):
    path = os.path.join(results, "map.json")
    doc = json_object(read_json(path), path)
    bounds = json_object(doc.get("bounds"), f"{path}: bounds")
    lo = json_vec3(bounds.get("lo"), f"{path}: bounds.lo")
    hi = json_vec3(bounds.get("hi"), f"{path}: bounds.hi")
    if not np.all(hi > lo):
        raise InputError(f"{path}: bounds.hi must exceed bounds.lo")
    spheres = []
    for i, s in enumerate(json_list(doc.get("spheres"), f"{path}: spheres")):
        s = json_object(s, f"{path}: spheres[{i}]")
        spheres.append((json_vec3(s.get("center"), f"{path}: spheres[{i}].center"),
                        json_number(s.get("radius"), f"{path}: spheres[{i}].radius")))
    cylinders = []
    for i, c in enumerate(json_list(doc.get("cylinders"), f"{path}: cylinders")):
        c = json_object(c, f"{path}: cylinders[{i}]")
        cylinders.append((json_vec3(c.get("base"), f"{path}: cylinders[{i}].base"),
                          json_number(c.get("radius"), f"{path}: cylinders[{i}].radius"),
                          json_number(c.get("height"), f"{path}: cylinders[{i}].height")))
    meshes = []
    for i, m in enumerate(json_list(doc.get("meshes"), f"{path}: meshes")):
        m = json_object(m, f"{path}: meshes[{i}]")
        try:
            vertices = np.array(json_list(m.get("vertices"), f"{path}: meshes[{i}].vertices"), dtype=float)
            triangles = np.array(json_list(m.get("triangles"), f"{path}: meshes[{i}].triangles"), dtype=int)
        except (TypeError, ValueError):
            raise InputError(f"{path}: meshes[{i}]: vertices and triangles must be lists of 3 numbers") from None
        if len(triangles) == 0:
            continue
        if vertices.ndim != 2 or vertices.shape[1] != 3 or triangles.ndim != 2 or triangles.shape[1] != 3:
            raise InputError(f"{path}: meshes[{i}]: vertices and triangles must be lists of 3 numbers")
        if triangles.min() < 0 or triangles.max() >= len(vertices):
            raise InputError(f"{path}: meshes[{i}]: triangle index out of range")
        meshes.append((vertices, triangles))
    scenarios = []
    for i, s in enumerate(json_list(doc.get("scenarios"), f"{path}: scenarios")):
        s = json_object(s, f"{path}: scenarios[{i}]")
        name = s.get("name")
        if not isinstance(name, str) or not name:
            raise InputError(f"{path}: scenarios[{i}].name must be a non-empty string")
        scenarios.append(name)
    return {"lo": lo, "hi": hi, "spheres": spheres, "cylinders": cylinders, "meshes": meshes,
            "scenarios": scenarios}


def trajectory_columns(index):
    """t and the positions of the first pursuer and evader: pursuer_0_x, ... (files written before issue 37
    named the only agent of a role pursuer_x, ...)."""
    p, e = ("pursuer_0", "evader_0") if "pursuer_0_x" in index else ("pursuer", "evader")
    return ("t",) + tuple(f"{a}_{c}" for a in (p, e) for c in "xyz")


def read_trajectory(path):
    index, rows = read_csv(path, ())
    columns = trajectory_columns(index)
    missing = [c for c in columns if c not in index]
    if missing:
        raise InputError(f"{path}: missing column(s) {', '.join(missing)}")
    if not rows:
        raise InputError(f"{path}: no rows (row 0 is the start)")
    columns = list(columns) + (["distance"] if "distance" in index else [])
    data = np.empty((len(rows), len(columns)))
    for r, row in enumerate(rows):
        for c, name in enumerate(columns):
            data[r, c] = parse_float(row[index[name]], f"{path}:{r + 2}: {name}")
    traj = {"t": data[:, 0], "pursuer": data[:, 1:4], "evader": data[:, 4:7]}
    traj["distance"] = data[:, 7] if "distance" in index else np.linalg.norm(data[:, 1:4] - data[:, 4:7], axis=1)
    return traj


def read_runs_repeat0(results):
    """(scenario, algorithm) -> outcome fields of repeat 0 from runs.csv; {} when the file is absent."""
    path = os.path.join(results, "runs.csv")
    if not os.path.exists(path):
        return {}
    index, rows = read_csv(path, ("scenario", "algorithm", "repeat", "outcome"))
    out = {}
    for line, row in enumerate(rows, start=2):
        if parse_int(row[index["repeat"]], f"{path}:{line}: repeat") != 0:
            continue
        fields = {"outcome": row[index["outcome"]]}
        for name in ("capture_time_s", "episode_time_s", "final_distance_m"):
            if name in index:
                fields[name] = parse_float(row[index[name]], f"{path}:{line}: {name}")
        out[(row[index["scenario"]], row[index["algorithm"]])] = fields
    return out


# ----------------------------------------------------------------------------------------------------------------
# Output


def save_figure(fig, path):
    """Saves `fig` as PNG to a temporary file next to `path`, then renames it (never a half-written PNG)."""
    folder, name = os.path.split(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format="png", dpi=DPI, metadata=SAVE_METADATA)
        os.chmod(tmp, 0o666 & ~UMASK)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    finally:
        plt.close(fig)


def current_umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


UMASK = current_umask()


def fmt_num(x, digits=3):
    if x is None or not math.isfinite(x):
        return "n/a"
    return f"{x:.{digits}g}"


def fmt_p(p):
    if p is None or not math.isfinite(p):
        return "n/a"
    if p < 1e-4:
        return f"{p:.0e}".replace("e-0", "e-")
    return f"{p:.2g}"


# ----------------------------------------------------------------------------------------------------------------
# 3D helpers


def sphere_quads(center, radius, n_az=14, n_el=8):
    """Quadrilaterals approximating a sphere, shape (n_az * n_el, 4, 3)."""
    az = np.linspace(0.0, 2.0 * np.pi, n_az + 1)
    el = np.linspace(0.0, np.pi, n_el + 1)
    a, e = np.meshgrid(az, el)
    pts = np.stack([np.cos(a) * np.sin(e), np.sin(a) * np.sin(e), np.cos(e)], axis=-1) * radius + center
    return grid_quads(pts)


def grid_quads(pts):
    """Quads of a (rows, cols, 3) grid of points."""
    return np.stack([pts[:-1, :-1], pts[:-1, 1:], pts[1:, 1:], pts[1:, :-1]], axis=2).reshape(-1, 4, 3)


def cylinder_polygons(base, radius, height, n=20):
    """Side quads and the two caps of a vertical cylinder standing on `base`."""
    ang = np.linspace(0.0, 2.0 * np.pi, n + 1)
    ring = np.stack([np.cos(ang) * radius, np.sin(ang) * radius, np.zeros_like(ang)], axis=-1) + base
    top = ring + np.array([0.0, 0.0, height])
    side = list(grid_quads(np.stack([ring, top], axis=0)))
    return side + [ring[:-1], top[:-1]]


def shaded_colors(polygons, rgb, alpha, light=(-0.4, -0.5, 0.77)):
    """RGBA per polygon, brighter where its normal faces the light (Poly3DCollection of matplotlib 3.6 has no
    shading of its own)."""
    if not polygons:
        return np.zeros((0, 4))
    light = np.asarray(light) / np.linalg.norm(light)
    shade = np.empty(len(polygons))
    for i, poly in enumerate(polygons):
        poly = np.asarray(poly)
        normal = np.cross(poly[1] - poly[0], poly[2] - poly[0])
        if np.linalg.norm(normal) < 1e-12 and len(poly) > 3:
            normal = np.cross(poly[2] - poly[0], poly[3] - poly[0])
        norm = np.linalg.norm(normal)
        shade[i] = abs(np.dot(normal, light)) / norm if norm > 0 else 0.5
    rgba = np.empty((len(polygons), 4))
    rgba[:, :3] = np.clip(np.asarray(rgb)[None, :] * (0.55 + 0.6 * shade[:, None]), 0.0, 1.0)
    rgba[:, 3] = alpha
    return rgba


def box_edges(lo, hi):
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    edges = []
    for i in range(8):
        for j in range(i + 1, 8):
            if np.count_nonzero(corners[i] != corners[j]) == 1:
                edges.append([corners[i], corners[j]])
    return edges


def orthonormal_basis(axis):
    axis = axis / np.linalg.norm(axis)
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return axis, u, np.cross(axis, u)


# ----------------------------------------------------------------------------------------------------------------
# Figure 1: trajectories


def split_trajectory_name(stem, scenarios, algorithms):
    """'<scenario>_<algorithm>' -> (scenario, algorithm), preferring known names (either may hold '_')."""
    for s in sorted(scenarios, key=len, reverse=True):
        if stem.startswith(s + "_") and len(stem) > len(s) + 1:
            return s, stem[len(s) + 1:]
    for a in sorted(algorithms, key=len, reverse=True):
        if stem.endswith("_" + a) and len(stem) > len(a) + 1:
            return stem[: -len(a) - 1], a
    if "_" not in stem.strip("_"):
        return None
    s, a = stem.rsplit("_", 1)
    return s, a


def outcome_text(algorithm, traj, run):
    t_end = traj["t"][np.isfinite(traj["t"])]
    t_end = t_end[-1] if len(t_end) else math.nan
    d = traj["distance"][np.isfinite(traj["distance"])]
    d_end = d[-1] if len(d) else math.nan
    if run is not None:
        outcome = run["outcome"]
        if math.isfinite(run.get("final_distance_m", math.nan)):
            d_end = run["final_distance_m"]
        captured = outcome == "capture"
        if captured and math.isfinite(run.get("capture_time_s", math.nan)):
            t_end = run["capture_time_s"]
        elif math.isfinite(run.get("episode_time_s", math.nan)):
            t_end = run["episode_time_s"]
        return f"{algorithm}: {outcome} at {fmt_num(t_end)} s, d = {d_end:.2f} m", captured
    return f"{algorithm}: ended at {fmt_num(t_end)} s, d = {d_end:.2f} m", None


def last_finite(points):
    ok = np.all(np.isfinite(points), axis=1)
    return points[ok][-1] if np.any(ok) else None


def first_finite(points):
    ok = np.all(np.isfinite(points), axis=1)
    return points[ok][0] if np.any(ok) else None


def plot_trajectories(results):
    arena = read_map(results)
    folder = os.path.join(results, "trajectories")
    if not os.path.isdir(folder):
        raise InputError(f"{folder}: missing")
    runs = read_runs_repeat0(results)
    known_algorithms = set(KNOWN_ALGORITHMS) | {a for _, a in runs}
    found = {}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".csv"):
            continue
        parts = split_trajectory_name(name[:-4], arena["scenarios"], known_algorithms)
        if parts is None:
            raise InputError(f"{os.path.join(folder, name)}: name is not <scenario>_<algorithm>.csv")
        found.setdefault(parts[0], {})[parts[1]] = read_trajectory(os.path.join(folder, name))
    scenarios = list(arena["scenarios"]) + sorted(set(found) - set(arena["scenarios"]), key=natural_key)
    if not scenarios:
        raise InputError(f"{folder}: no trajectories and map.json lists no scenarios")
    algorithms = order_algorithms(a for by_alg in found.values() for a in by_alg)

    n = len(scenarios)
    ncols = 1 if n == 1 else 2
    nrows = math.ceil(n / ncols)
    row_h, title_h, legend_h = 5.6, 0.75, 0.7
    fig_h = (row_h + title_h) * nrows + legend_h + 0.35
    fig = plt.figure(figsize=(7.2 * ncols, fig_h))
    lo, hi = arena["lo"], arena["hi"]
    obstacle_polys = []
    for center, radius in arena["spheres"]:
        obstacle_polys.extend(sphere_quads(center, radius))
    for base, radius, height in arena["cylinders"]:
        obstacle_polys.extend(cylinder_polygons(base, radius, height))
    obstacle_colors = shaded_colors(obstacle_polys, (0.56, 0.56, 0.56), alpha=0.25)
    edges = box_edges(lo, hi)
    unknown_outcome = False

    for k, scenario in enumerate(scenarios):
        ax = fig.add_subplot(nrows, ncols, k + 1, projection="3d", computed_zorder=False)
        for vertices, triangles in arena["meshes"]:
            ax.add_collection3d(Poly3DCollection(vertices[triangles], facecolor="#c8b68e", edgecolor="none",
                                                 alpha=0.35, zorder=1))
        if obstacle_polys:
            ax.add_collection3d(Poly3DCollection(obstacle_polys, facecolors=obstacle_colors, edgecolor="none",
                                                 zorder=1))
        ax.add_collection3d(Line3DCollection(edges, colors="#555555", linewidths=0.7, zorder=2))
        lines = []
        for alg in algorithms:
            traj = found.get(scenario, {}).get(alg)
            if traj is None:
                continue
            color = algorithm_color(alg)
            p, e = traj["pursuer"], traj["evader"]
            ax.plot(p[:, 0], p[:, 1], p[:, 2], color=color, lw=1.6, ls="-", zorder=4)
            ax.plot(e[:, 0], e[:, 1], e[:, 2], color=color, lw=1.4, ls=(0, (4, 2)), zorder=4)
            text, captured = outcome_text(alg, traj, runs.get((scenario, alg)))
            lines.append(text)
            p0, e0, p1, e1 = first_finite(p), first_finite(e), last_finite(p), last_finite(e)
            # Every algorithm starts a scenario from the same places: neutral start markers.
            if p0 is not None:
                ax.scatter(*p0, marker="o", s=55, color="white", edgecolors="black", linewidths=1.2, zorder=5,
                           depthshade=False)
            if e0 is not None:
                ax.scatter(*e0, marker="^", s=65, color="white", edgecolors="black", linewidths=1.2, zorder=5,
                           depthshade=False)
            if captured is None:  # no runs.csv row: the outcome is unknown
                unknown_outcome = True
                for end in (p1, e1):
                    if end is not None:
                        ax.scatter(*end, marker="s", s=45, color=color, edgecolors="black", linewidths=0.6,
                                   zorder=6, depthshade=False)
            elif captured and e1 is not None:
                ax.scatter(*e1, marker="*", s=190, color=color, edgecolors="black", linewidths=0.7, zorder=6,
                           depthshade=False)
            else:
                for end in (p1, e1):
                    if end is not None:
                        ax.scatter(*end, marker="X", s=70, color=color, edgecolors="black", linewidths=0.6,
                                   zorder=6, depthshade=False)
        # The zoomed 3D box reaches past the axes' own rectangle: do not clip what is drawn inside it.
        for artist in list(ax.lines) + list(ax.collections):
            artist.set_clip_on(False)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(tuple(hi - lo), zoom=1.18)
        ax.view_init(elev=24, azim=-58)
        ax.set_xlabel("x (m)", labelpad=2)
        ax.set_ylabel("y (m)", labelpad=2)
        ax.set_zlabel("z (m)", labelpad=0)
        ax.tick_params(labelsize=8, pad=0)
        if not lines:
            lines.append("no trajectory")
        ax.set_title(scenario + "\n" + "\n".join(lines), fontsize=9.5, loc="center", pad=2)

    handles = [Line2D([], [], color=algorithm_color(a), lw=2.5, label=a) for a in algorithms]
    handles += [
        Line2D([], [], color="black", lw=1.6, ls="-", label="pursuer path"),
        Line2D([], [], color="black", lw=1.4, ls=(0, (4, 2)), label="evader path"),
        Line2D([], [], color="white", marker="o", markerfacecolor="white", markeredgecolor="black", ms=7,
               mew=1.2, label="pursuer start"),
        Line2D([], [], color="white", marker="^", markerfacecolor="white", markeredgecolor="black", ms=8,
               mew=1.2, label="evader start"),
        Line2D([], [], color="white", marker="*", markerfacecolor="#bbbbbb", markeredgecolor="black", ms=13,
               label="capture"),
        Line2D([], [], color="white", marker="X", markerfacecolor="#bbbbbb", markeredgecolor="black", ms=8,
               label="end without capture"),
        Patch(facecolor="#8f8f8f", alpha=0.35, label="obstacle"),
    ]
    if unknown_outcome:
        handles.insert(-1, Line2D([], [], color="white", marker="s", markerfacecolor="#bbbbbb",
                                  markeredgecolor="black", ms=7, label="end (outcome not in runs.csv)"))
    fig.legend(handles=handles, loc="lower center", ncol=min(len(handles), 6 if len(algorithms) > 2 else 5),
               fontsize=9, frameon=False)
    fig.suptitle("Evaluation episodes after training (repeat 0)", fontsize=12, y=0.995)
    fig.subplots_adjust(left=0.0, right=0.97, bottom=legend_h / fig_h, top=1 - (title_h + 0.35) / fig_h,
                        wspace=0.02, hspace=title_h / row_h)
    save_figure(fig, os.path.join(results, "trajectories.png"))


# ----------------------------------------------------------------------------------------------------------------
# Figure 2: comparison


def read_summary(results):
    path = os.path.join(results, "summary.json")
    doc = json_object(read_json(path), path)
    scenarios = doc.get("scenarios")
    scenarios = {} if scenarios is None else json_object(scenarios, f"{path}: scenarios")
    out = {}
    for name, sc in scenarios.items():
        where = f"{path}: scenarios.{name}"
        sc = json_object(sc, where)
        algs = sc.get("algorithms")
        algs = {} if algs is None else json_object(algs, f"{where}.algorithms")
        entry = {"algorithms": {}, "comparisons": []}
        for alg, s in algs.items():
            w = f"{where}.algorithms.{alg}"
            s = json_object(s, w)
            stats = {"runs": json_number(s.get("runs", 0), f"{w}.runs"),
                     "captures": json_number(s.get("captures", 0), f"{w}.captures")}
            for metric in ("pursuer_path_m", "capture_time_s"):
                m = s.get(metric)
                m = {} if m is None else json_object(m, f"{w}.{metric}")
                stats[metric] = {k: json_number(m.get(k), f"{w}.{metric}.{k}") for k in ("mean", "lo", "hi")}
            entry["algorithms"][alg] = stats
        for i, c in enumerate(json_list(sc.get("comparisons"), f"{where}.comparisons")):
            w = f"{where}.comparisons[{i}]"
            c = json_object(c, w)
            if not all(isinstance(c.get(k), str) for k in ("a", "b", "metric")):
                raise InputError(f"{w}: a, b and metric must be strings")
            entry["comparisons"].append({"a": c["a"], "b": c["b"], "metric": c["metric"],
                                         "t_test_p": json_number(c.get("t_test_p"), f"{w}.t_test_p"),
                                         "wilcoxon_p": json_number(c.get("wilcoxon_p"), f"{w}.wilcoxon_p")})
        out[name] = entry
    time_limit = doc.get("time_limit_s")
    time_limit = json_number(time_limit, f"{path}: time_limit_s") if time_limit is not None else math.nan
    return out, time_limit


def p_value_lines(comparisons, metric, algorithms):
    rank = {a: i for i, a in enumerate(algorithms)}
    chosen = [c for c in comparisons if c["metric"] == metric]
    chosen.sort(key=lambda c: (rank.get(c["a"], 99), rank.get(c["b"], 99), c["a"], c["b"]))
    return [f"{c['a']} vs {c['b']}: p = {fmt_p(c['t_test_p'])} / {fmt_p(c['wilcoxon_p'])}" for c in chosen]


def plot_comparison(results):
    summary, time_limit = read_summary(results)
    scenarios = sorted(summary, key=natural_key)
    algorithms = order_algorithms(a for sc in summary.values() for a in sc["algorithms"])
    panels = (("pursuer_path_m", "pursuer_path_m", "mean pursuer path length (m)",
               "pursuer path length, all runs"),
              ("capture_time_s", "time_to_capture_s", "mean capture time (s)",
               "capture time, captured runs only"))
    n_pairs = max([len(p_value_lines(summary[s]["comparisons"], m, algorithms)) for s in scenarios
                   for _, m, _, _ in panels] + [0])
    width_in = max(8.0, 2.9 * max(len(scenarios), 1) + 1.5)
    panel_h = 3.6 + 0.16 * n_pairs
    fig, axes = plt.subplots(2, 1, figsize=(width_in, 2 * panel_h + 0.9))
    n_alg = max(len(algorithms), 1)
    bar_w = min(0.8 / n_alg, 0.3)
    group_w = bar_w * n_alg
    x = np.arange(len(scenarios))
    for ax, (metric, test_metric, ylabel, title) in zip(axes, panels):
        top = 0.0
        for j, alg in enumerate(algorithms):
            xs, means, err_lo, err_hi, err_x = [], [], [], [], []
            for i, s in enumerate(scenarios):
                stats = summary[s]["algorithms"].get(alg)
                if stats is None:
                    continue
                m = stats[metric]
                xpos = x[i] - group_w / 2 + bar_w * (j + 0.5)
                mean = m["mean"]
                label_y = 0.0
                if math.isfinite(mean):
                    xs.append(xpos)
                    means.append(mean)
                    label_y = mean
                    if math.isfinite(m["lo"]) and math.isfinite(m["hi"]):
                        err_x.append(xpos)
                        err_lo.append(max(mean - m["lo"], 0.0))
                        err_hi.append(max(m["hi"] - mean, 0.0))
                        label_y = max(mean, m["hi"])
                top = max(top, label_y)
                runs, caps = stats["runs"], stats["captures"]
                count = f"{fmt_num(caps, 6)}/{fmt_num(runs, 6)}"
                missing = "no capture" if metric == "capture_time_s" else "no data"
                ax.annotate(count if math.isfinite(mean) else f"{count}\n({missing})", (xpos, label_y),
                            xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", fontsize=7.5,
                            color="#333333")
            ax.bar(xs, means, bar_w * 0.92, color=algorithm_color(alg), label=alg, zorder=2)
            if err_x:
                ax.errorbar(err_x, [means[xs.index(v)] for v in err_x], yerr=[err_lo, err_hi], fmt="none",
                            ecolor="black", elinewidth=1.0, capsize=3, zorder=3)
        ax.set_ylim(0, top * 1.16 if top > 0 else 1.0)
        ax.set_xticks(x)
        ax.set_xticklabels(scenarios, fontsize=10.5, fontweight="bold")
        ax.tick_params(axis="x", length=0, pad=4)
        below_ticks = matplotlib.transforms.offset_copy(ax.get_xaxis_transform(), fig=fig, y=-20, units="points")
        for i, s in enumerate(scenarios):
            lines = p_value_lines(summary[s]["comparisons"], test_metric, algorithms)
            if lines:
                ax.text(x[i], 0, "\n".join(lines), transform=below_ticks, ha="center", va="top", fontsize=7.5,
                        linespacing=1.35, color="#222222")
        ax.set_xlim(-0.6, len(scenarios) - 0.4 if scenarios else 0.6)
        ax.set_ylabel(ylabel)
        ax.set_title(title + " (bars: mean with 95% t interval; above: captures/runs)", fontsize=10)
        ax.grid(axis="y", color="#dddddd", zorder=0)
        ax.set_axisbelow(True)
        if not scenarios:
            ax.text(0.5, 0.5, "summary.json holds no scenarios", transform=ax.transAxes, ha="center",
                    va="center", color="#777777")
    handles = [Patch(color=algorithm_color(a), label=a) for a in algorithms]
    limit = f", time limit {fmt_num(time_limit)} s" if math.isfinite(time_limit) else ""
    note = ("under each scenario: paired p-values, t-test / Wilcoxon signed-rank (top: path length; bottom: time "
            f"to capture with runs without capture counted at the time limit{limit})")
    fig.legend(handles=handles, loc="upper center", ncol=max(len(handles), 1), fontsize=9, frameon=False,
               bbox_to_anchor=(0.5, 1.0))
    fig.text(0.5, 0.005, note, ha="center", va="bottom", fontsize=7.5, color="#333333", wrap=True)
    fig.tight_layout(rect=(0, 0.03, 1, 0.965), h_pad=1.2)
    save_figure(fig, os.path.join(results, "comparison.png"))


# ----------------------------------------------------------------------------------------------------------------
# Figure 3: learning curves


def trailing_mean(values, window):
    """Per row, at each column: the mean of the last `window` finite values up to it (fewer at the start), nan
    before the first. Gaps (the opponent-pool episodes) are skipped, so a sparse co-learning curve still
    averages `window` episodes."""
    out = np.full(values.shape, np.nan)
    for r in range(values.shape[0]):
        valid = np.isfinite(values[r])
        sums = np.concatenate(([0.0], np.cumsum(values[r][valid])))
        k = np.cumsum(valid)  # finite values up to and including each column
        lo = np.maximum(k - window, 0)
        seen = k > 0
        out[r, seen] = (sums[k[seen]] - sums[lo[seen]]) / (k[seen] - lo[seen])
    return out


def mean_and_se(values):
    """Mean and standard error over axis 0, ignoring nan (se nan with fewer than two values)."""
    n = np.sum(np.isfinite(values), axis=0)
    with warnings.catch_warnings(), np.errstate(invalid="ignore", divide="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        mean = np.nanmean(values, axis=0) if values.size else np.array([])
        sd = np.nanstd(values, axis=0, ddof=1) if values.shape[0] > 1 else np.full(values.shape[1:], np.nan)
        se = np.where(n >= 2, sd / np.sqrt(np.maximum(n, 1)), np.nan)
    return mean, se


def read_learning_curves(results):
    """Per (scenario, algorithm): capture flags and episode times, repeats x episodes. Opponent-pool episodes
    (a FACL role against a classic opponent) are left out as nan, so that the curves show co-learning alone;
    also returns how many were left out."""
    path = os.path.join(results, "learning_curves.csv")
    index, rows = read_csv(path, ("scenario", "algorithm", "repeat", "episode", "pool_opponent", "captured",
                                  "episode_time_s"))
    i_s, i_a, i_r, i_e = index["scenario"], index["algorithm"], index["repeat"], index["episode"]
    i_o, i_c, i_t = index["pool_opponent"], index["captured"], index["episode_time_s"]
    groups = {}
    pool_episodes = 0
    for line, row in enumerate(rows, start=2):
        where = f"{path}:{line}"
        repeat = parse_int(row[i_r], f"{where}: repeat")
        episode = parse_int(row[i_e], f"{where}: episode")
        if repeat < 0 or episode < 0:
            raise InputError(f"{where}: negative repeat or episode")
        captured = parse_flag(row[i_c], f"{where}: captured")
        seconds = parse_float(row[i_t], f"{where}: episode_time_s")
        if row[i_o] != "":
            pool_episodes += 1
            captured = seconds = math.nan
        groups.setdefault((row[i_s], row[i_a]), []).append((repeat, episode, captured, seconds))
    return curve_arrays(groups), pool_episodes


def curve_arrays(groups):
    """{key: [(run, episode, captured, seconds), ...]} -> {key: (captured, times)}, each runs x episodes (runs
    in sorted order, nan where a run has no such episode)."""
    curves = {}
    for key, items in groups.items():
        runs = sorted({r for r, _, _, _ in items})
        slot = {r: i for i, r in enumerate(runs)}
        n_ep = max(e for _, e, _, _ in items) + 1
        captured = np.full((len(runs), n_ep), np.nan)
        times = np.full((len(runs), n_ep), np.nan)
        for r, e, c, t in items:
            captured[slot[r], e] = c
            times[slot[r], e] = t
        curves[key] = (captured, times)
    return curves


def draw_curves(axes, curve, window, color, label):
    """Draws (captured, times) on (rate axis, time axis): the trailing mean over `window` episodes, mean over
    the runs with a +-1 standard error band where there are two runs or more. Returns whether it drew a band."""
    band = False
    for ax, values in zip(axes, curve):
        episodes = np.arange(values.shape[1])
        mean, se = mean_and_se(trailing_mean(values, window))
        ax.plot(episodes, mean, color=color, lw=1.5, label=label)
        if np.any(np.isfinite(se)):
            band = True
            ax.fill_between(episodes, mean - se, mean + se, color=color, alpha=0.2, lw=0)
    return band


def plot_learning(results):
    curves, pool_episodes = read_learning_curves(results)
    scenarios = sorted({s for s, _ in curves}, key=natural_key)
    algorithms = order_algorithms(a for _, a in curves)
    n = max(len(scenarios), 1)
    ncols = 1 if n == 1 else 2
    nrows = math.ceil(n / ncols)
    w = MOVING_AVERAGE_EPISODES
    block_h, top_h, bottom_h = 5.0, 0.95, 0.5
    fig_h = block_h * nrows + top_h + bottom_h
    fig = plt.figure(figsize=(7.0 * ncols, fig_h))
    outer = fig.add_gridspec(nrows, ncols, left=0.07 if ncols > 1 else 0.12, right=0.98, top=1 - top_h / fig_h,
                             bottom=bottom_h / fig_h, wspace=0.2, hspace=0.2)
    repeat_counts = set()
    any_band = False
    for k in range(n):
        inner = outer[k // ncols, k % ncols].subgridspec(2, 1, hspace=0.07)
        ax_rate = fig.add_subplot(inner[0])
        ax_time = fig.add_subplot(inner[1], sharex=ax_rate)
        if not scenarios:
            ax_rate.text(0.5, 0.5, "learning_curves.csv holds no episodes", transform=ax_rate.transAxes,
                         ha="center", va="center", color="#777777")
        else:
            scenario = scenarios[k]
            ax_rate.set_title(scenario, fontsize=11, fontweight="bold")
            for alg in algorithms:
                if (scenario, alg) not in curves:
                    continue
                repeat_counts.add(curves[(scenario, alg)][0].shape[0])
                any_band |= draw_curves((ax_rate, ax_time), curves[(scenario, alg)], w, algorithm_color(alg), alg)
        ax_rate.set_ylim(-0.03, 1.03)
        ax_rate.set_ylabel("capture rate")
        ax_time.set_ylabel("episode time (s)")
        ax_time.set_xlabel("training episode")
        ax_rate.tick_params(labelbottom=False)
        for ax in (ax_rate, ax_time):
            ax.grid(color="#e3e3e3")
            ax.tick_params(labelsize=8.5)
        ax_time.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    handles = [Line2D([], [], color=algorithm_color(a), lw=2, label=a) for a in algorithms]
    if any_band:
        handles.append(Patch(color="#999999", alpha=0.35, label="±1 standard error over repeats"))
    fig.legend(handles=handles, loc="upper center", ncol=max(len(handles), 1), fontsize=9.5, frameon=False,
               bbox_to_anchor=(0.5, 1 - 0.4 / fig_h))
    if repeat_counts:
        counts = "/".join(str(c) for c in sorted(repeat_counts))
        over = f"mean over {counts} repeat{'s' if repeat_counts != {1} else ''}"
    else:
        over = "no data"
    which = "Co-learning episodes (opponent-pool episodes left out)" if pool_episodes else "Training episodes"
    fig.suptitle(f"{which}: trailing mean of {w} episodes, {over}", fontsize=12,
                 y=1 - 0.12 / fig_h, va="top")
    save_figure(fig, os.path.join(results, "learning.png"))


# ----------------------------------------------------------------------------------------------------------------
# Figure 4: Apollonius surfaces


def sphere_grid(center, radius, axis, max_angle, n_az=48, n_pol=28):
    """Points of a spherical cap around `axis` (half-angle max_angle; pi gives the whole sphere)."""
    axis, u, v = orthonormal_basis(axis)
    az = np.linspace(0.0, 2.0 * np.pi, n_az + 1)
    pol = np.linspace(0.0, max_angle, n_pol + 1)
    a, p = np.meshgrid(az, pol)
    dirs = (np.cos(p)[..., None] * axis + (np.sin(p) * np.cos(a))[..., None] * u
            + (np.sin(p) * np.sin(a))[..., None] * v)
    return center + radius * dirs


def read_apollonius(results):
    path = os.path.join(results, "apollonius.json")
    doc = json_object(read_json(path), path)
    p = json_vec3(doc.get("pursuer"), f"{path}: pursuer")
    e = json_vec3(doc.get("evader"), f"{path}: evader")
    surfaces = []
    for i, s in enumerate(json_list(doc.get("surfaces"), f"{path}: surfaces")):
        w = f"{path}: surfaces[{i}]"
        s = json_object(s, w)
        a = json_number(s.get("a"), f"{w}.a")
        kind = s.get("kind")
        if kind == "sphere":
            radius = json_number(s.get("radius"), f"{w}.radius")
            if not math.isfinite(radius) or radius <= 0:
                raise InputError(f"{w}.radius must be positive")
            surfaces.append({"a": a, "kind": kind, "center": json_vec3(s.get("center"), f"{w}.center"),
                             "radius": radius})
        elif kind == "plane":
            normal = json_vec3(s.get("normal"), f"{w}.normal")
            if np.linalg.norm(normal) == 0:
                raise InputError(f"{w}.normal must not be zero")
            surfaces.append({"a": a, "kind": kind, "point": json_vec3(s.get("point"), f"{w}.point"),
                             "normal": normal / np.linalg.norm(normal)})
        else:
            raise InputError(f"{w}.kind must be 'sphere' or 'plane'")
    cone = None
    if doc.get("pursuer_cone") is not None:
        c = json_object(doc["pursuer_cone"], f"{path}: pursuer_cone")
        axis = json_vec3(c.get("axis"), f"{path}: pursuer_cone.axis")
        half = json_number(c.get("half_angle_rad"), f"{path}: pursuer_cone.half_angle_rad")
        if np.linalg.norm(axis) > 0 and math.isfinite(half) and 0 < half < math.pi / 2:
            cone = (axis / np.linalg.norm(axis), half)
    speed_ratio = math.nan
    if isinstance(doc.get("vp"), (int, float)) and isinstance(doc.get("ve"), (int, float)) and doc["vp"] > 0:
        speed_ratio = doc["ve"] / doc["vp"]
    return p, e, surfaces, cone, speed_ratio


def surface_colors(grid, center, rgb, alpha, light):
    """RGBA per face of a (rows, cols, 3) surface grid, gently shaded by the outward normal (from `center`)."""
    mid = (grid[:-1, :-1] + grid[1:, 1:]) / 2
    normal = mid - center
    normal /= np.maximum(np.linalg.norm(normal, axis=-1, keepdims=True), 1e-12)
    intensity = 0.72 + 0.28 * (normal @ light)
    rgba = np.empty(mid.shape[:2] + (4,))
    rgba[..., :3] = np.clip(np.asarray(rgb)[None, None, :] * intensity[..., None], 0.0, 1.0)
    rgba[..., 3] = alpha
    return rgba


def plot_apollonius(results):
    p, e, surfaces, cone, speed_ratio = read_apollonius(results)
    pe = float(np.linalg.norm(p - e))
    if pe == 0:
        raise InputError(f"{os.path.join(results, 'apollonius.json')}: pursuer and evader coincide")
    # The view: P, E and every sphere no larger than twice |PE|; larger ones are drawn as the cap inside it.
    pts = [p, e]
    for s in surfaces:
        if s["kind"] == "sphere" and s["radius"] <= 2 * pe:
            pts += [s["center"] - s["radius"], s["center"] + s["radius"]]
    pts = np.array(pts)
    view_c = (pts.min(axis=0) + pts.max(axis=0)) / 2
    half = max(float(np.max(pts.max(axis=0) - pts.min(axis=0))) / 2, 0.6 * pe) * 1.02
    elev, azim = 20.0, -28.0
    camera = np.array([math.cos(math.radians(elev)) * math.cos(math.radians(azim)),
                       math.cos(math.radians(elev)) * math.sin(math.radians(azim)), math.sin(math.radians(elev))])
    light = np.array([-0.3, -0.5, 0.81])
    light /= np.linalg.norm(light)

    fig = plt.figure(figsize=(12.0, 8.0))
    ax = fig.add_axes((0.0, 0.0, 0.6, 0.93), projection="3d", computed_zorder=False)
    items = []  # (depth towards the camera, draw function): painted far to near
    handles = []

    def ratio_label(a):
        text = f"a = {a:.3g}"
        if math.isfinite(speed_ratio) and abs(a - speed_ratio) < 1e-12:
            text += " (= vE/vP)"
        return text

    def surface(grid, colors):
        def draw(zorder):
            ax.plot_surface(grid[..., 0], grid[..., 1], grid[..., 2], facecolors=colors, linewidth=0,
                            edgecolor="none", antialiased=True, shade=False, zorder=zorder)
        return draw

    below = sorted([s for s in surfaces if s["a"] < 1 and s["kind"] == "sphere"], key=lambda s: s["radius"])
    above = sorted([s for s in surfaces if s["a"] > 1 and s["kind"] == "sphere"], key=lambda s: s["radius"])
    yellows = ("#f7dc1e", "#f0a202", "#e8c547", "#d18b00")
    greens = ("#2ca02c", "#78c679", "#1b7a3a", "#a1d99b")
    for group, palette, side in ((below, yellows, "E"), (above, greens, "P")):
        for i, s in enumerate(group):
            color = palette[i % len(palette)]
            rgb = matplotlib.colors.to_rgb(color)
            c, r = s["center"], s["radius"]
            if r <= 2 * pe:
                grid = sphere_grid(c, r, np.array([0.0, 0.0, 1.0]), math.pi)
                extent = f"R = {r:.3g} m"
                alpha, depth = 0.3, float(np.dot(c, camera))
            else:
                to_view = view_c - c
                axis = to_view if np.linalg.norm(to_view) > 0 else np.array([0.0, 0.0, 1.0])
                grid = sphere_grid(c, r, axis, math.asin(min(1.0, half / r)), n_az=36, n_pol=6)
                extent = f"R = {r:.4g} m (only the cap near P and E)"
                alpha, depth = 0.18, float(np.dot(c + r * axis / np.linalg.norm(axis), camera))
            items.append((depth, surface(grid, surface_colors(grid, c, rgb, alpha, light))))
            inside = np.max(np.abs(c - view_c)) <= half
            if inside:
                items.append((float(np.dot(c, camera)) + 1e-9,
                              lambda z, c=c, color=color: ax.scatter(*c, marker="x", s=45, color=color,
                                                                     linewidths=2.0, depthshade=False, zorder=z)))
            where = f"O_AC = ({', '.join(f'{v:.3g}' for v in c)})" + ("" if inside else " (off view)")
            rel = "<" if s["a"] < 1 else ">"
            handles.append((s["a"], Patch(facecolor=color, alpha=0.6,
                                          label=f"{ratio_label(s['a'])} {rel} 1: sphere around {side}\n{where}\n"
                                                f"{extent}")))
    for s in surfaces:
        if s["kind"] != "plane":
            continue
        n, u, v = orthonormal_basis(s["normal"])
        # The patch is centred on the point of the plane nearest the view centre.
        centre = view_c - np.dot(view_c - s["point"], n) * n
        g = np.linspace(-half * 0.95, half * 0.95, 2)
        gu, gv = np.meshgrid(g, g)
        grid = centre + gu[..., None] * u + gv[..., None] * v
        colors = np.tile(np.array(matplotlib.colors.to_rgba("#1f77b4", 0.25)), (1, 1, 1))
        items.append((float(np.dot(centre, camera)), surface(grid, colors)))
        handles.append((s["a"], Patch(facecolor="#1f77b4", alpha=0.5,
                                      label=f"{ratio_label(s['a'])}: plane (bisector of PE)\n"
                                            f"through ({', '.join(f'{x:.3g}' for x in s['point'])}), "
                                            f"normal ({', '.join(f'{x:.3g}' for x in n)})")))
    if cone is not None:
        axis, angle = cone
        length = 0.4 * pe
        _, u, v = orthonormal_basis(axis)
        az = np.linspace(0.0, 2.0 * np.pi, 49)
        sl = np.linspace(0.0, length / math.cos(angle), 2)
        a, s_ = np.meshgrid(az, sl)
        dirs = (math.cos(angle) * axis + math.sin(angle) * (np.cos(a)[..., None] * u + np.sin(a)[..., None] * v))
        grid = p + s_[..., None] * dirs
        colors = np.tile(np.array(matplotlib.colors.to_rgba("#d62728", 0.25)), (1, 48, 1))
        items.append((float(np.dot(p + 0.5 * length * axis, camera)), surface(grid, colors)))
        handles.append((math.inf, Patch(facecolor="#d62728", alpha=0.4,
                             label=f"pursuer's motion cone about P→E\nhalf-angle "
                                   f"asin(vE/vP) = {math.degrees(angle):.1f}°")))
    for zorder, (_, draw) in enumerate(sorted(items, key=lambda item: item[0]), start=1):
        draw(zorder)
    top = len(items) + 10
    ax.plot(*np.stack([p, e], axis=1), color="#333333", lw=1.0, ls=":", zorder=top)
    ax.scatter(*p, s=70, color="#b22222", edgecolors="black", depthshade=False, zorder=top + 1)
    ax.scatter(*e, s=70, color="#1a237e", edgecolors="black", depthshade=False, zorder=top + 1)
    offset = 0.04 * half
    ax.text(*(p + offset), "P", fontsize=12, fontweight="bold", color="#b22222", zorder=top + 2)
    ax.text(*(e + offset), "E", fontsize=12, fontweight="bold", color="#1a237e", zorder=top + 2)
    handles = [
        Line2D([], [], color="white", marker="o", markerfacecolor="#b22222", markeredgecolor="black", ms=8,
               label=f"P = ({', '.join(f'{x:.3g}' for x in p)}) pursuer"),
        Line2D([], [], color="white", marker="o", markerfacecolor="#1a237e", markeredgecolor="black", ms=8,
               label=f"E = ({', '.join(f'{x:.3g}' for x in e)}) evader"),
        Line2D([], [], color="#555555", marker="x", lw=0, ms=7, mew=1.8, label="O_AC: centre of a sphere"),
    ] + [h for _, h in sorted(handles, key=lambda item: item[0])]
    for setter, k in ((ax.set_xlim, 0), (ax.set_ylim, 1), (ax.set_zlim, 2)):
        setter(view_c[k] - half, view_c[k] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.tick_params(labelsize=8)
    fig.legend(handles=handles, loc="center left", bbox_to_anchor=(0.63, 0.5), fontsize=9, frameon=False,
               labelspacing=1.0, handlelength=1.6)
    ratio = f"; vE/vP = {speed_ratio:.3g}" if math.isfinite(speed_ratio) else ""
    fig.suptitle(f"Generalized Apollonius surfaces a = |EC|/|PC| for P and E, |PE| = {pe:.3g} m{ratio}",
                 fontsize=11.5, y=0.98)
    save_figure(fig, os.path.join(results, "apollonius.png"))


# ----------------------------------------------------------------------------------------------------------------


PLOTTERS = {"trajectories": plot_trajectories, "comparison": plot_comparison, "learning": plot_learning,
            "apollonius": plot_apollonius}


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="plot_paper.py", description="Draws the paper's figures from a peg-paper result folder.")
    parser.add_argument("results", metavar="RESULTS_DIR", help="the folder peg-paper wrote (--out)")
    parser.add_argument("--only", metavar="NAME", nargs="+", action="extend", default=None,
                        help=f"draw only these figures ({', '.join(FIGURES)})")
    args = parser.parse_args(argv)
    if args.only is not None:
        names = []
        for name in args.only:
            base = name[:-4] if name.endswith(".png") else name
            if base not in FIGURES:
                parser.error(f"--only: unknown figure '{name}' (valid: {', '.join(FIGURES)})")
            if base not in names:
                names.append(base)
        args.only = names
    return args


def main(argv):
    args = parse_args(argv)
    if not os.path.isdir(args.results):
        print(f"error: {args.results}: not a folder", file=sys.stderr)
        return 2
    failed = False
    for name in args.only or FIGURES:
        try:
            PLOTTERS[name](args.results)
        except InputError as e:
            print(f"error: {name}.png not written: {e}", file=sys.stderr)
            failed = True
        except OSError as e:
            print(f"error: {name}.png not written: {e}", file=sys.stderr)
            failed = True
    return 2 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
