"""What the sweep end-to-end scripts share about output folders: the journal as it grows, and result files
compared byte for byte.

    from result_folders import journal_runs, same_results, wait_for_runs
"""
import filecmp
import os
import time

from checks import check


def journal_runs(out):
    """Complete run lines in OUT/runs.journal (0 when there is none yet)."""
    try:
        with open(os.path.join(out, "runs.journal"), "rb") as f:
            return max(f.read().count(b"\n") - 1, 0)
    except FileNotFoundError:
        return 0


def wait_for_runs(proc, out, runs, timeout=120.0):
    """Waits until the journal holds `runs` finished runs while the sweep still works; False if it ended first."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            return False
        if journal_runs(out) >= runs:
            return True
        time.sleep(0.01)
    return False


def result_files(folder):
    """Every file of an output folder but the wall-clock one (timing.json), by relative path."""
    found = set()
    for root, _, files in os.walk(folder):
        for name in files:
            rel = os.path.relpath(os.path.join(root, name), folder)
            if rel != "timing.json":
                found.add(rel)
    return found


def same_results(reference, folder, what):
    """Checks that `folder` holds the files of `reference`, byte-identical (timing.json aside)."""
    ref, got = result_files(reference), result_files(folder)
    if not check(ref == got, f"{what}: files differ: missing {sorted(ref - got)}, extra {sorted(got - ref)}"):
        return False
    differ = [f for f in sorted(ref) if not filecmp.cmp(os.path.join(reference, f), os.path.join(folder, f), shallow=False)]
    return check(not differ, f"{what}: not byte-identical to the reference sweep: {differ}")


def small_sweeps(bin_dir):
    """The three experiment binaries' small sweeps, by name: commands without --out and --threads; 16 runs each,
    of a few tens of milliseconds in a Release build (and small enough for the sanitizer build too). peg-paper's
    robust arm trains with the opponent pool, so its episodes' opponents must survive the journal too."""
    paper, matchup, generalize = (os.path.join(bin_dir, p) for p in ("peg-paper", "peg-matchup", "peg-generalize"))
    return {
        "peg-paper": [paper, "--seed", "7", "--repeats", "2", "--episodes", "20", "--algorithms", "peg3d,robust",
                      "--no-plots", "--plain-progress"],
        "peg-matchup": [matchup, "--seed", "7", "--repeats", "4", "--episodes", "20", "--pursuers", "facl,pn",
                        "--evaders", "facl,flee", "--plain-progress"],
        "peg-generalize": [generalize, "--seed", "7", "--repeats", "4", "--episodes", "20", "--eval-maps",
                           "maps/paper.yaml", "--plain-progress"],
    }
