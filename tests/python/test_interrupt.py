"""Ctrl-C during long vector steps is honoured: the KeyboardInterrupt reaches Python at the end of the step
that was running (the step releases the GIL; the signal is checked before it returns)."""

import os
import signal
import subprocess
import sys
import time

# A child started from a background job inherits SIGINT ignored, and then Python installs no KeyboardInterrupt
# handler: give it the default disposition, as a terminal would (CTest does this itself; a plain pytest run from
# a background job, such as tools/test.sh --python-versions started with &, does not).
def _sigint_default():
    signal.signal(signal.SIGINT, signal.SIG_DFL)


PROGRAM = """
import peg3d, numpy as np
v = peg3d.vector_env(num_envs=4096, threads=2, opponents={"evader": "flee"})
v.reset(seed=0)
a = {"pursuer": np.zeros((4096, 1, 2))}
print("stepping", flush=True)
while True:
    v.step(a)
"""


def test_sigint_stops_a_loop_of_long_steps():
    p = subprocess.Popen([sys.executable, "-c", PROGRAM], stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=_sigint_default,
                         env=dict(os.environ), text=True)
    assert p.stdout.readline().strip() == "stepping"
    time.sleep(0.5)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        _, err = p.communicate(timeout=10)
    finally:
        p.kill()
    assert time.monotonic() - sent < 5
    assert p.returncode != 0
    assert "KeyboardInterrupt" in err


# The C++ batch's steps driven from C (map() over the module's step, consumed by a deque): no Python bytecode
# runs between them, so the interpreter never looks at the signal itself. Only the step's own check can raise
# it; without it this loop would never end.
C_LOOP = """
import collections, itertools
import peg3d, numpy as np
v = peg3d.vector_env(num_envs=512, threads=2, opponents={"evader": "flee"})
v.reset(seed=0)
a = np.zeros((512, 2, 2))
print("stepping", flush=True)
collections.deque(map(v._batch.step, itertools.repeat(a)), maxlen=0)
"""


def test_the_step_itself_raises_the_interrupt():
    p = subprocess.Popen([sys.executable, "-c", C_LOOP], stdout=subprocess.PIPE, stderr=subprocess.PIPE, preexec_fn=_sigint_default,
                         env=dict(os.environ), text=True)
    assert p.stdout.readline().strip() == "stepping"
    time.sleep(0.5)
    p.send_signal(signal.SIGINT)
    try:
        _, err = p.communicate(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("the step did not raise the interrupt") from None
    assert p.returncode != 0
    assert "KeyboardInterrupt" in err
