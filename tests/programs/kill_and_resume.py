"""A study killed with SIGKILL at random moments and resumed each time ends with the record of
the run that was never interrupted (issue #17, item 2).

usage: kill_and_resume.py GROWSHELL OUT_DIR [CORRECTOR]

CORRECTOR (newton, the default, or chord) is the scene's continuation.corrector: the chord
starts each step from the previous sample's factorisation, which a resumed run must rebuild
exactly.

Runs a small cone_branch study (`growshell run`) once without interruption, then again into
another directory, killed (kill -9) ten times and resumed with --resume after each kill, and
once more to its end. The kills are spread over the record: each comes a random delay (up to
a third of a step's time, so that some fall inside the writing of a row, a state or
events.json) after the record reached a row count drawn at random (seeded, the same on every
run of the test) between its first and its last row; one comes during the start, before any
row. Then every
row of branch.csv must equal the uninterrupted run's to 1e-8 (relative, with an absolute floor
of 1e-12 for values at rounding, such as the S4 defect of a symmetric state), the arclength
must go on without a jump or a repeated row, events.json must list the same events at the same
phi_e, results.json the same key values, and states/ must hold one state per row, no
temporary, and each state equal to the uninterrupted run's byte for byte (the resumed trace
takes the very steps of the one that was killed, to the last bit). Prints what differs and exits 1 if anything does.
"""

import csv
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time

SCENE = {"thickness": 0.04, "mesh": {"size_slope": 0.25},
         "continuation": {"phi_max": 2.0}, "output": {"write_vtk": False}}
KILLS = 10
RELATIVE, ABSOLUTE = 1e-8, 1e-12


def row_count(directory):
    """Rows of DIR/branch.csv written so far (a partial last line counts), 0 without one."""
    try:
        with open(os.path.join(directory, "branch.csv"), "rb") as f:
            return max(0, f.read().count(b"\n") - 1)
    except OSError:
        return 0


def run(growshell, scene, out, resume, kill_at_rows=None, then=0.0):
    """Runs the study; with kill_at_rows, kills it with SIGKILL `then` seconds after its record
    has that many rows (if it is still running). Returns (return code, whether it was killed,
    stdout + stderr)."""
    command = [growshell, "run", scene, "--out", out] + (["--resume"] if resume else [])
    with open(os.path.join(os.path.dirname(out), "log.txt"), "w+") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        killed = False
        if kill_at_rows is not None:
            while process.poll() is None and row_count(out) < kill_at_rows:
                time.sleep(0.005)
            time.sleep(then)
            if process.poll() is None:
                process.send_signal(signal.SIGKILL)
                killed = True
        process.wait()
        log.seek(0)
        return process.returncode, killed, log.read()


def rows(directory):
    with open(os.path.join(directory, "branch.csv"), newline="") as f:
        return list(csv.reader(f))


def close(a, b):
    if a == b:
        return True
    x, y = float(a), float(b)
    if x != x and y != y:  # both NaN
        return True
    return abs(x - y) <= RELATIVE * max(abs(x), abs(y)) + ABSOLUTE


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    growshell, out = sys.argv[1], sys.argv[2]
    corrector = sys.argv[3] if len(sys.argv) == 4 else "newton"
    if corrector not in ("newton", "chord"):
        sys.exit(f"CORRECTOR must be newton or chord, not {corrector!r}")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    scene = os.path.join(out, "small.json")
    with open(scene, "w") as f:
        json.dump(dict(SCENE, continuation=dict(SCENE["continuation"], corrector=corrector)), f)
    failures = []

    reference = os.path.join(out, "uninterrupted")
    started = time.monotonic()
    rc, _, log = run(growshell, scene, reference, resume=False)
    duration = time.monotonic() - started
    if rc != 0:
        sys.exit(f"the uninterrupted run failed ({rc}):\n{log}")
    total = row_count(reference)
    step_time = duration / max(1, total)

    killed_dir = os.path.join(out, "killed")
    moments = random.Random(17)
    # The first kill during the start; the others after rows drawn over the whole record.
    targets = [0] + sorted(moments.sample(range(1, total - 1), KILLS - 1))
    kills, killed_at = 0, []
    for target in targets:
        resume = os.path.isdir(killed_dir)
        then = moments.uniform(0.0, step_time / 3) if target > 0 else 0.2 * duration
        rc, killed, log = run(growshell, scene, killed_dir, resume, kill_at_rows=target,
                              then=then)
        if rc != 0 and not killed:
            failures.append(f"a {'resumed' if resume else 'first'} run failed ({rc}):\n{log}")
            break
        if killed:
            kills += 1
            killed_at.append(row_count(killed_dir))
    if kills < KILLS - 1:
        failures.append(f"only {kills} of {KILLS} runs were killed before they ended")
    rc, _, log = run(growshell, scene, killed_dir, resume=True)
    if rc != 0:
        failures.append(f"the last resume failed ({rc}):\n{log}")

    if not failures:
        a, b = rows(reference), rows(killed_dir)
        if a[0] != b[0]:
            failures.append(f"branch.csv columns differ: {a[0]} against {b[0]}")
        if len(a) != len(b):
            failures.append(f"branch.csv has {len(b) - 1} rows, the uninterrupted run "
                            f"{len(a) - 1}")
        for i, (x, y) in enumerate(zip(a[1:], b[1:])):
            for column, p, q in zip(a[0], x, y):
                if column == "corrector_iterations":
                    continue  # a resumed start is corrected again, in 0 or 1 iterations
                if not close(p, q):
                    failures.append(f"row {i + 1}, {column}: {q}, uninterrupted {p}")
        s = a[0].index("arclength")
        arclength = [float(r[s]) for r in b[1:]]
        if any(t <= u for u, t in zip(arclength, arclength[1:])):
            failures.append("the arclength of the resumed record does not increase")

        def load(name, directory):
            with open(os.path.join(directory, name)) as f:
                return json.load(f)
        events_a, events_b = load("events.json", reference), load("events.json", killed_dir)
        kinds = lambda events: [e.get("kind") for e in events]
        if kinds(events_a) != kinds(events_b):
            failures.append(f"events {kinds(events_b)}, uninterrupted {kinds(events_a)}")
        for e, f in zip(events_a, events_b):
            if not close(str(e["phi_e"]), str(f["phi_e"])):
                failures.append(f"event {e.get('kind')} at {f['phi_e']}, uninterrupted "
                                f"{e['phi_e']}")
        results_a, results_b = load("results.json", reference), load("results.json", killed_dir)
        for key, value in results_a.items():
            other = results_b.get(key)
            if isinstance(value, float) and key != "wall_seconds":
                if not isinstance(other, float) or not close(str(value), str(other)):
                    failures.append(f"results.json {key}: {other}, uninterrupted {value}")
        states = sorted(os.listdir(os.path.join(killed_dir, "states")))
        if len(states) != len(b) - 1 or any(not n.endswith(".state") for n in states):
            failures.append(f"states/ holds {len(states)} files for {len(b) - 1} rows: "
                            f"{[n for n in states if not n.endswith('.state')]}")
        # Every saved state (x, its tangent, the next step and the reduced state the symmetric
        # subspace traced) is the uninterrupted run's, byte for byte.
        def state_bytes(directory, name):
            try:
                with open(os.path.join(directory, "states", name), "rb") as f:
                    return f.read()
            except OSError:
                return None
        differing = [n for n in states if state_bytes(killed_dir, n) != state_bytes(reference, n)]
        if differing:
            failures.append(f"{len(differing)} of {len(states)} saved states differ from the "
                            f"uninterrupted run's, from {differing[0]} on")

    for f in failures:
        print("FAILED:", f)
    print(f"{kills} kills, at rows {killed_at} of {total}; uninterrupted run {duration:.1f} s")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
