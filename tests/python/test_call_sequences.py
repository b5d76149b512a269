"""No sequence of Python calls can crash the interpreter: random sequences of resets, steps with good and bad
actions, state queries and closes, drawn by hypothesis; each call either works or raises a Python error."""

import numpy as np
from hypothesis import HealthCheck, given, settings
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
