"""What parallel_env and vector_env share: finding maps and configurations as the programs do, the
keyword arguments as the C++ batch takes them, and the spaces."""

import os
from pathlib import Path

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


def controllers(opponents):
    """{"evader_0": "flee", "pursuer": "policy.json"} as (agent or role, policy name or file) pairs."""
    if opponents is None:
        return []
    if not isinstance(opponents, dict):
        raise TypeError("opponents: a dict of agent (or role) names to policies")
    out = []
    for key, policy in opponents.items():
        if not isinstance(key, str) or not isinstance(policy, (str, os.PathLike)):
            raise TypeError("opponents: names to policy names or files")
        p = str(policy)
        out.append((key, resolve(p) if (p.endswith(".json") or os.sep in p) else p))
    return out


def make_batch(map, config, scenario, settings, opponents, games, threads, seed, neighbours, cache=True, record=False,
               extra_controllers=()):
    """The C++ batch. `extra_controllers`: (agent or role, policy) pairs after those of `opponents`, which they
    override ("" gives an agent back to the caller)."""
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
    return _core.Batch(resolve(map), config_source(config), overrides(settings), list(scenario), int(games),
                       int(threads), int(seed), int(neighbours), controllers(opponents) + list(extra_controllers), cache,
                       record)


def frame_renderer(batch):
    """The images of render_mode "rgb_array": 640 x 480, from a fixed camera (src/view/frame_renderer.hpp)."""
    return _core.FrameRenderer(batch, 640, 480)


def role_spaces(batch, pursuer):
    low, high = batch.observation_bounds()
    bound = np.float32(batch.action_bound(pursuer))
    obs = Box(low, high, dtype=np.float32)
    act = Box(np.full(2, -bound, dtype=np.float32), np.full(2, bound, dtype=np.float32), dtype=np.float32)
    return obs, act


def check_seed(seed):
    if seed is None:
        return None
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= int(seed) < 2**64:
        raise ValueError("seed: None or an integer in [0, 2^64)")
    return int(seed)


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
