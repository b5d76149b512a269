"""Policy files of networks trained from Python (docs/python.md, "Policy files"): peg3d-mlp documents that the C++
side plays wherever a policy plays (peg-matchup, peg-league, peg-collide cases, the batch's opponents), fed
exactly the observation its agent has in the batch. A file records that observation's segments; the C++ loader
refuses it for an agent whose observation differs, naming the first segment that does."""

import json
import os

import numpy as np

from . import _core
from ._roles import ROLES

FORMAT = "peg3d-mlp"
VERSION = 2


def _segments(observation):
    """[{"name", "size", "unit"}] of a segment list (env.observation_segments[agent], or the dicts themselves)."""
    out = []
    for s in observation:
        if isinstance(s, dict):
            name, size, unit = s["name"], s["size"], s["unit"]
        else:
            name, size, unit = s.name, s.size, s.unit
        out.append({"name": str(name), "size": int(size), "unit": str(unit)})
    if not out:
        raise ValueError("observation: the network's observation segments (env.observation_segments[agent])")
    return out


def _floats(values, what, shape=None):
    a = np.asarray(values, dtype=np.float64)
    if shape is not None and a.shape != shape:
        raise ValueError(f"{what}: shape {a.shape}, expected {shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{what}: every value must be finite")
    return a


def save_policy(path, *, role, observation, layers, action_bound, input_mean=None, input_std=None, action_std=None,
                play="mean", **extra):
    """Writes a network as a peg3d-mlp file (version 2), atomically.

    role: "pursuer" or "evader". observation: the segments it reads, in order (env.observation_segments[agent] of
    the environment it trained in, or a LearnerEnv's observation_segments). layers: [(weights, bias), ...], weights
    out x in (a torch Linear's weight), tanh after every layer but the last, whose 2 outputs are squashed as
    action_bound * tanh(out) (rad). input_mean, input_std: the inputs' normalization, x = (obs - mean) / std
    (default 0 and 1). action_std: the Gaussian's standard deviations (rad), which play="sample" draws with.
    extra: more keys to record (the C++ loader ignores them): what trained it, its opponents, ...
    """
    if role not in ROLES:
        raise ValueError(f"role: 'pursuer' or 'evader', not {role!r}")
    segments = _segments(observation)
    inputs = sum(s["size"] for s in segments)
    mean = np.zeros(inputs) if input_mean is None else _floats(input_mean, "input_mean", (inputs,))
    std = np.ones(inputs) if input_std is None else _floats(input_std, "input_std", (inputs,))
    if not np.all(std > 0):
        raise ValueError("input_std: every value must be > 0")
    doc_layers, width = [], inputs
    for k, (weights, bias) in enumerate(layers):
        w = _floats(weights, f"layers[{k}].weights")
        if w.ndim != 2 or w.shape[1] != width:
            raise ValueError(f"layers[{k}].weights: shape {w.shape}, expected (out, {width})")
        b = _floats(bias, f"layers[{k}].bias", (w.shape[0],))
        doc_layers.append({"weights": w.tolist(), "bias": b.tolist()})
        width = w.shape[0]
    if width != 2:
        raise ValueError(f"layers: the last layer has {width} outputs, not 2 (d_alpha, d_theta)")
    bound = float(action_bound)
    if not 0 < bound <= 3.2:
        raise ValueError(f"action_bound: {bound} is not in (0, pi] rad")
    doc = {"format": FORMAT, "version": VERSION, "role": role, "observation": segments, "inputs": inputs,
           "action_bound": bound, "input_mean": mean.tolist(), "input_std": std.tolist(), "layers": doc_layers}
    if action_std is not None:
        doc["action_std"] = _floats(action_std, "action_std", (2,)).tolist()
    if play not in ("mean", "sample"):
        raise ValueError(f"play: 'mean' or 'sample', not {play!r}")
    if play == "sample" and action_std is None:
        raise ValueError("play='sample' needs action_std")
    doc["play"] = play
    for key, value in extra.items():
        if key in doc:
            raise ValueError(f"{key}: a key of the format itself")
        doc[key] = value
    _write_atomically(path, doc)
    return path


MIXTURE_FORMAT = "peg3d-mixture"


def read_policy(path):
    """A policy file's document (a dict), checked for its format: a peg3d-mlp network, or a peg3d-mixture (what
    peg3d.selfplay ships: {"role", "members": [{"policy": player or file, "weight"}]}, one member played per episode
    with probability weight / total). A mixture's members each gain "path", the file a member names (relative to the
    mixture's folder; None for a classic player), and "document", that file's document (a peg3d-mlp network's as
    read_policy reads it, a FACL file's as written; None for a player). ValueError naming the file and field (a
    mixture is checked by the C++ loader, players::load_saved_policy: peg3d.InputError, a ValueError)."""
    with open(path) as f:
        doc = json.load(f)
    kind = doc.get("format") if isinstance(doc, dict) else None
    if kind == FORMAT:
        return doc
    if kind != MIXTURE_FORMAT:
        raise ValueError(f"{path}: not a {FORMAT} or {MIXTURE_FORMAT} file")

    # The C++ loader's checks (players::load_saved_policy: version, role, members, weights, no nested mixture, the
    # members' roles and FACL configurations), so that Python refuses what the programs refuse, with their messages.
    role = doc.get("role") if doc.get("role") in ROLES else "pursuer"
    _core.check_policy(os.fspath(path), role)
    for m in doc["members"]:
        source = m["policy"]
        m["path"], m["document"] = None, None
        if source.endswith(".json") or "/" in source:
            member_path = os.path.join(os.path.dirname(os.fspath(path)), source)
            with open(member_path) as f:
                member = json.load(f)
            m["path"] = member_path
            m["document"] = read_policy(member_path) if member.get("format") == FORMAT else member
    return doc


def upgrade_policy(path, env, agent, out=None):
    """Re-saves a version 1 peg3d-mlp file (which records only its input count) as version 2, recording the
    observation `agent` has in `env`: the environment it was trained in (a parallel_env, vector_env, LearnerEnv or
    LearnerVectorEnv made with the same map, settings and neighbours). Writes `out` (default: over `path`) and
    returns it. ValueError when that observation's length is not the file's input count."""
    doc = read_policy(path)
    if doc["format"] != FORMAT:
        raise ValueError(f"{path}: a {doc['format']} file: upgrade its {FORMAT} members one by one")
    segments = env.observation_segments if isinstance(env.observation_segments, tuple) else \
        env.observation_segments[agent]
    segments = _segments(segments)
    inputs = sum(s["size"] for s in segments)
    if doc.get("inputs") != inputs:
        raise ValueError(f"{path}: {doc.get('inputs')} inputs, but {agent}'s observation in this environment has "
                         f"{inputs} ({', '.join(s['name'] for s in segments)})")
    doc["version"] = VERSION
    doc["observation"] = segments
    _write_atomically(out or path, doc)
    return out or path


def _write_atomically(path, doc):
    path = os.fspath(path)
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w") as f:
        json.dump(doc, f, allow_nan=False)
        f.write("\n")
    os.replace(tmp, path)


__all__ = ["FORMAT", "MIXTURE_FORMAT", "VERSION", "read_policy", "save_policy", "upgrade_policy"]
