"""No sequence of Python calls can crash the interpreter: random sequences of resets, steps with good and bad
actions, state queries and closes, drawn by hypothesis; each call either works or raises a Python error."""

import sys

import numpy as np
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

import peg3d

ENVS = {}


def parallel():
    if "p" not in ENVS:
        ENVS["p"] = dict(opponents={"evader": "flee"}, set={"time_limit": 1.0})
    return peg3d.parallel_env(**ENVS["p"])


values = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10, 10), st.none(), st.text(max_size=3))
actions = st.one_of(
    st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=0, max_size=4).map(np.array),
    st.tuples(st.floats(-10, 10), st.floats(-10, 10)).map(np.array),
    values,
)
calls = st.lists(st.one_of(
    st.tuples(st.just("reset"), st.one_of(st.none(), st.integers(-5, 2**64 + 5), st.text(max_size=2))),
    st.tuples(st.just("step"), st.dictionaries(st.sampled_from(["pursuer_0", "evader_0", "x"]), actions, max_size=3)),
    st.tuples(st.just("step_raw"), values),
    st.tuples(st.just("state"), st.none()),
    st.tuples(st.just("space"), st.sampled_from(["pursuer_0", "evader_0", 3])),
    st.tuples(st.just("close"), st.none()),
), max_size=25)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(calls)
def test_random_parallel_call_sequences_never_crash(sequence):
    env = parallel()
    for name, arg in sequence:
        try:
            if name == "reset":
                env.reset(seed=arg)
            elif name == "step":
                env.step(arg)
            elif name == "step_raw":
                env.step(arg)
            elif name == "state":
                env.state()
            elif name == "space":
                env.observation_space(arg)
            else:
                env.close()
        except (ValueError, TypeError, RuntimeError, KeyError, OverflowError):
            pass


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.sampled_from(["reset", "step", "state"]),
                          st.one_of(st.integers(-3, 5), st.floats(allow_nan=True), st.none())), max_size=15))
def test_random_vector_call_sequences_never_crash(sequence):
    v = peg3d.vector_env(num_envs=2, threads=2, opponents={"evader": "flee"}, set={"time_limit": 1.0})
    for name, arg in sequence:
        try:
            if name == "reset":
                v.reset(seed=arg)
            elif name == "step":
                a = np.full((2, 1, 2), 0.1 if arg is None else arg, dtype=np.float64)
                v.step({"pursuer": a})
            else:
                v.state(arg)
        except (ValueError, TypeError, RuntimeError, IndexError, OverflowError):
            pass


# Settings drawn from real keys with values in and out of their ranges (non-finite, of the wrong type), and keys
# that do not exist: every environment either builds or raises a documented error, and then plays or refuses.
def mostly(valid, *invalid):
    """Valid values four times as often as the invalid ones, so that most environments get built and played."""
    return st.one_of(valid, valid, valid, valid, st.sampled_from(invalid))


SETTING_VALUES = {
    "time_limit": mostly(st.floats(0.5, 3.0), float("nan"), float("inf"), -1.0, "x"),
    "pursuer.speed": mostly(st.floats(0.1, 3.0), float("nan"), True, -1.0),
    "capture_distance": mostly(st.floats(0.1, 2.0), float("-inf"), 0),
    "pursuer.lidar.azimuth_rays": mostly(st.integers(1, 20), 1e9, 2.5, -2),
    "pursuer.lidar.range": mostly(st.floats(1.0, 30.0), float("nan"), -1.0),
    "pursuer.map.enabled": mostly(st.booleans(), 2, "yes"),
    "pursuer.map.resolution": mostly(st.sampled_from([0.1, 0.25, 1.0]), 0.0, -1.0, float("nan"), 1e300),
    "pursuer.map.clamp_max": mostly(st.sampled_from([0.97, 0.6]), 0.5, 1.0, float("nan")),
    "pursuer.sight.enabled": st.booleans(),
    "pursuer.sight.fov": mostly(st.floats(10.0, 360.0), float("inf"), -10.0),
    "pursuer.camera.width": mostly(st.integers(1, 12), 10**6, -1),
    "pursuer.camera.height": mostly(st.integers(1, 9), 0),
    "no.such.key": st.integers(0, 1),
}
ERRORS = (ValueError, TypeError, RuntimeError, KeyError, MemoryError, OverflowError)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.dictionaries(st.sampled_from(sorted(SETTING_VALUES)), st.none(), max_size=4).flatmap(
           lambda keys: st.fixed_dictionaries({k: SETTING_VALUES[k] for k in keys})),
       st.sampled_from(["parallel", "vector", "learner", "learner_vector"]),
       mostly(st.integers(0, 3), -1, 17), mostly(st.integers(1, 4), 0, -1),
       st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.floats(-1, 1)), min_size=2, max_size=2),
       st.one_of(st.none(), st.integers(0, 2**64 - 1), st.lists(st.one_of(st.none(), st.integers(0, 9),
                                                                          st.floats(allow_nan=True)), max_size=4)),
       st.one_of(st.none(), st.lists(st.booleans(), min_size=0, max_size=4)))
def test_random_settings_seeds_masks_and_actions_never_crash(chosen, kind, neighbours, games, action, seed, mask):
    sets = dict({"time_limit": 1.0}, **chosen)
    try:
        if kind == "parallel":
            env = peg3d.parallel_env(opponents={"evader": "flee"}, set=sets, neighbours=neighbours)
        elif kind == "vector":
            env = peg3d.vector_env(num_envs=games, threads=2, opponents={"evader": "flee"}, set=sets, neighbours=neighbours)
        elif kind == "learner":
            env = peg3d.LearnerEnv(set=sets, neighbours=neighbours)
        else:
            env = peg3d.LearnerVectorEnv(num_envs=games, threads=2, set=sets, neighbours=neighbours)
    except ERRORS:
        event(f"refused when built: {str(sys.exc_info()[1])[:60]}")
        return
    event(f"built: {kind}")
    for _ in range(3):
        try:
            if kind == "learner_vector":
                options = None if mask is None else {"reset_mask": np.array(mask, dtype=bool)}
                env.reset(seed=seed, options=options)
                env.step(np.tile(np.array(action), (env.num_envs, 1)))
            elif kind == "vector":
                env.reset(seed=seed if not isinstance(seed, list) else None)
                env.step({"pursuer": np.full((env.num_envs, 1, 2), action[0])})
            elif kind == "learner":
                env.reset(seed=seed if not isinstance(seed, list) else None)
                env.step(np.array(action))
            else:
                env.reset(seed=seed if not isinstance(seed, list) else None)
                env.step({a: np.array(action) for a in env.agents})
        except ERRORS:
            pass
    env.close()
