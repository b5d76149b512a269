"""What the end-to-end scripts share: checks that record failures, running a program, and the verdict.

A script puts tests/support on sys.path and imports this module:

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
    from checks import check, failures, run, verdict
"""
import subprocess

failures = []


def check(cond, what, verbose=False):
    """Records `what` as a failure (and prints it) unless `cond`; with `verbose`, prints passes too."""
    if cond:
        if verbose:
            print("ok   " + what)
    else:
        failures.append(what)
        print("FAIL: " + what)
    return cond


def run(cmd, **kw):
    """Runs an argument vector (no shell), its output captured as text."""
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def verdict():
    """Prints the count of failures and returns the script's exit status."""
    print("ok" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0
