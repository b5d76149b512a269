"""What parallel_env and vector_env share: finding maps and configurations as the programs do, the
keyword arguments as the C++ batch takes them, and the spaces."""

import math
import os
from pathlib import Path
from typing import NamedTuple

import numpy as np

from . import _core
from gymnasium.spaces import Box

PACKAGE_DIR = Path(__file__).resolve().parent


def data_dir():
    """The maps and assets: $PEG3D_DATA_DIR, else those installed beside the compiled module (pip install,
    peg3d/data; an editable install runs this file from the source tree but the module from site-packages),
    else those staged beside the build's module (build/share/peg3d beside build/python)."""
    env = os.environ.get("PEG3D_DATA_DIR")
    if env:
        return Path(env)
    installed = Path(_core.__file__).resolve().parent / "data"
    if installed.is_dir():
        return installed
    return PACKAGE_DIR.parent.parent / "share" / "peg3d"


def resolve(path):
    """A map or file as given when it exists, else the shipped one of that name (maps/paper.yaml)."""
    p = Path(path)
    if p.is_absolute() or p.exists():
        return str(p)
    shipped = data_dir() / p
    return str(shipped) if shipped.exists() else str(p)


def config_source(config):
    """A preset name (peg3d.PRESETS) as it is, a JSON file resolved like a map."""
    if not isinstance(config, (str, os.PathLike)):
        raise TypeError("config: a preset name or a JSON file")
    c = str(config)
    return resolve(c) if c.endswith(".json") else c


def overrides(settings):
    """{"pursuer.speed": 1.2, "evader.guard.faces": False} as the programs' --set key=value."""
    if settings is None:
        return []
    if not isinstance(settings, dict):
        raise TypeError("set: a dict of configuration fields to values")
    out = []
    for key, value in settings.items():
        if not isinstance(key, str):
            raise TypeError("set: keys are field names")
        if isinstance(value, bool):
            value = "true" if value else "false"
        out.append(f"{key}={value}")
    return out


def _policy(p, field):
    if not isinstance(p, (str, os.PathLike)):
        raise TypeError(f"{field}: a policy name or file, not {type(p).__name__}")
    p = str(p)
    return resolve(p) if (p.endswith(".json") or os.sep in p) else p


def _weight(w, field):
    if isinstance(w, bool) or not isinstance(w, (int, float, np.integer, np.floating)):
        raise TypeError(f"{field}: a weight is a number, not {type(w).__name__}")
    w = float(w)
    if not math.isfinite(w) or w < 0:
        raise ValueError(f"{field}: a weight is finite and >= 0, not {w!r}")
    return w


def mixture(policy, field):
    """One agent's (or role's) C++ players as [(policy, weight), ...]: a policy name or file plays every episode;
    {policy: weight, ...} or [(policy, weight), ...] draws one per episode, with probability weight / total."""
    if isinstance(policy, (str, os.PathLike)):
        return [(_policy(policy, field), 1.0)]
    if isinstance(policy, dict):
        pairs = list(policy.items())
    elif isinstance(policy, (list, tuple)):
        pairs = list(policy)
        if not all(isinstance(p, (list, tuple)) and len(p) == 2 for p in pairs):
            raise TypeError(f"{field}: a mixture is a dict of policies to weights or a list of (policy, weight) pairs")
    else:
        raise TypeError(f"{field}: a policy name, a policy file or a mixture {{policy: weight, ...}}, "
                        f"not {type(policy).__name__}")
    if not pairs:
        raise ValueError(f"{field}: a mixture has at least one member")
    out = [(_policy(p, f"{field}.{k}"), _weight(w, f"{field}.{k}.weight")) for k, (p, w) in enumerate(pairs)]
    if not sum(w for _, w in out) > 0:
        raise ValueError(f"{field}: a mixture's weights sum to more than 0")
    return out


def controllers(opponents):
    """{"evader_0": "flee", "pursuer": "policy.json", "evader": {"flee": 0.5, "hide": 0.5}} as (agent or role,
    [(policy name or file, weight), ...]) pairs."""
    if opponents is None:
        return []
    if not isinstance(opponents, dict):
        raise TypeError("opponents: a dict of agent (or role) names to policies")
    out = []
    for key, policy in opponents.items():
        if not isinstance(key, str):
            raise TypeError("opponents: names to policy names, files or mixtures")
        out.append((key, mixture(policy, f"opponents.{key}")))
    return out


def make_batch(map, config, scenario, settings, opponents, games, threads, seed, neighbours, cache=True, record=False,
               extra_controllers=(), memory_budget=None):
    """The C++ batch. `extra_controllers`: (agent or role, policy) pairs after those of `opponents`, which they
    override ("" gives an agent back to the caller). `memory_budget`: bytes the games may take (None: three
    quarters of the machine's memory); a batch estimated to need more raises peg3d.MemoryBudgetError."""
    if not isinstance(map, (str, os.PathLike)):
        raise TypeError("map: a map file")
    if isinstance(scenario, str):
        scenario = [scenario]
    elif scenario is None:
        scenario = []
    elif not isinstance(scenario, (list, tuple)) or not all(isinstance(s, str) for s in scenario):
        raise TypeError("scenario: a scenario name, a list of them or None")
    for name, v in (("num_envs", games), ("threads", threads), ("neighbours", neighbours)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)):
            raise TypeError(f"{name}: an integer")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= int(seed) < 2**64:
        raise ValueError("seed: an integer in [0, 2^64)")
    if memory_budget is not None and (isinstance(memory_budget, bool) or not isinstance(memory_budget, (int, np.integer))
                                      or not 0 < memory_budget < 2**63):
        raise ValueError(f"memory_budget: None or a positive number of bytes, not {memory_budget!r}")
    return _core.Batch(resolve(map), config_source(config), overrides(settings), list(scenario), int(games),
                       int(threads), int(seed), int(neighbours),
                       controllers(opponents) + [(key, [(p, 1.0)]) for key, p in extra_controllers], cache,
                       record, int(memory_budget or 0))


def frame_renderer(batch):
    """The images of render_mode "rgb_array": 640 x 480, from a fixed camera (src/view/frame_renderer.hpp)."""
    return _core.FrameRenderer(batch, 640, 480)


class Segment(NamedTuple):
    """A named part of an agent's observation, as the C++ library lays it out (src/game/observation.hpp): entries
    [offset, offset + size) of the observation, in `unit`, each within [low, high], laid out as `shape` (row-major:
    (size,) for a list, (rows, columns) for an image)."""
    name: str
    offset: int
    size: int
    unit: str
    low: np.ndarray
    high: np.ndarray
    meaning: str
    shape: tuple

    @property
    def slice(self):
        """Where its entries lie in an observation: observation[segment.slice]."""
        return slice(self.offset, self.offset + self.size)

    def space(self):
        """A gymnasium Box of its entries, shaped as the segment is."""
        return Box(self.low.reshape(self.shape), self.high.reshape(self.shape), dtype=np.float32)


def segments_of(batch, i):
    """Agent i's observation segments, from the C++ batch."""
    return tuple(Segment(d["name"], d["offset"], d["size"], d["unit"], np.asarray(d["low"]), np.asarray(d["high"]),
                         d["meaning"], tuple(d["shape"])) for d in batch.observation_segments(i))


def agent_spaces(batch, i):
    """Agent i's observation space (its own observation's length and bounds) and action space."""
    low, high = batch.observation_bounds(i)
    bound = np.float32(batch.action_bound(i < batch.pursuers))
    obs = Box(low, high, dtype=np.float32)
    act = Box(np.full(2, -bound, dtype=np.float32), np.full(2, bound, dtype=np.float32), dtype=np.float32)
    return obs, act


def segment_named(segments, name):
    """The segment called `name` of a list; KeyError naming the ones there are."""
    for s in segments:
        if s.name == name:
            return s
    raise KeyError(f"{name}: no such segment (this observation has {', '.join(s.name for s in segments)})")


def segment_view(batch, segments_by_index, name):
    """The segment `name` of the agents that have it, as one read-only view of the batch's observations:
    (games, agents with it, *shape), the same memory. Those agents must be consecutive and share its offset and
    shape (ValueError otherwise). Returns (view, Box of one game's view: each agent's bounds)."""
    having = [(i, s) for i, segs in segments_by_index for s in segs if s.name == name]
    if not having:
        raise KeyError(f"{name}: no agent's observation has this segment")
    indices = [i for i, _ in having]
    first = having[0][1]
    if indices != list(range(indices[0], indices[-1] + 1)) or any(
            s.offset != first.offset or s.shape != first.shape for _, s in having):
        raise ValueError(f"{name}: the agents that have it are not consecutive, or lay it out differently; "
                         "read it per agent with observation[segment.slice]")
    view = batch.segment_view(first.offset, list(first.shape), indices[0], len(indices))
    low = np.stack([seg.low.reshape(seg.shape) for _, seg in having])
    high = np.stack([seg.high.reshape(seg.shape) for _, seg in having])
    return view, Box(low, high, dtype=np.float32)


def compat_offset(segments_by_agent, name):
    """The offset of segment `name` shared by every agent that has it (-1 when none has it): the old attributes
    `ranges_offset` and `sight_offset` as the segments give them."""
    offsets = {s.offset for segs in segments_by_agent for s in segs if s.name == name}
    return offsets.pop() if len(offsets) == 1 else -1


def largest_size(segments_by_agent, name):
    """The most entries segment `name` has among the agents (0 when none has it)."""
    return max((s.size for segs in segments_by_agent for s in segs if s.name == name), default=0)


def check_seed(seed, field="seed"):
    """A seed as an int, or None; ValueError naming `field` for anything else (a float, a string, a bool, NaN)."""
    if seed is None:
        return None
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= int(seed) < 2**64:
        raise ValueError(f"{field}: None or an integer in [0, 2^64), not {seed!r}")
    return int(seed)


class Closable:
    """An environment that refuses every call once closed: RuntimeError, the same in every front."""

    _closed = False

    def _check_open(self):
        if self._closed:
            raise RuntimeError("peg3d: the environment is closed")


class Rebuilt:
    """Pickling and copying an environment make it anew from the arguments it was made with (`_made_with`, set
    first thing by its __init__): a fresh environment on the same map and settings, not reset. Its state (games
    in progress, seeds, closed or not) stays behind: a C++ batch has no portable bytes, and what ships an
    environment to workers (SuperSuit, Ray, cloudpickle) wants the constructor, not the state."""

    _made_with = None

    @staticmethod
    def remember(arguments):
        """The constructor's arguments from its locals() (called first thing): self and __class__ left out."""
        return {k: v for k, v in arguments.items() if k not in ("self", "__class__")}

    def __reduce__(self):
        if self._made_with is None:
            raise TypeError(f"{type(self).__name__}: made without its arguments, it cannot be rebuilt")
        return (_rebuild, (type(self), self._made_with))


def _rebuild(cls, arguments):
    return cls(**arguments)


def check_action(name, a, shape):
    """An action as a float64 array of `shape`, or ValueError naming the agent (or role). Whether its values can
    be stepped (finite) is the C++ step's check: it raises peg3d.InputError, a ValueError, and steps nothing."""
    try:
        x = np.asarray(a)
    except Exception as e:  # noqa: BLE001 - anything numpy cannot read is a bad action
        raise ValueError(f"{name}: the action is not an array of numbers ({e})") from None
    if x.dtype.kind not in "f":
        raise ValueError(f"{name}: the action's dtype is {x.dtype}, not floating point")
    if x.shape != shape:
        raise ValueError(f"{name}: the action's shape is {x.shape}, not {shape}")
    return x.astype(np.float64, copy=False)
