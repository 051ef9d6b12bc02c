#!/usr/bin/env python3
"""Kills a growshell study with SIGKILL at random moments, resumes it after each kill, and
checks that it ends with the record of the run that was never interrupted (issue #17, item 2).

usage: kill_and_resume_study.py GROWSHELL SCENE OUT [--kills N] [--seed S]

Runs `GROWSHELL run SCENE` once without interruption into OUT/uninterrupted, then again into
OUT/killed, killed N times (default 10), each run resumed with --resume, and once more to its
end. Each kill comes when the records below OUT/killed hold a number of rows (all branch.csv
files together) drawn at random (seeded by S, default 17) over the uninterrupted run's, then
after a random delay of up to three rows' time: the kills are spread over every stage, and some
fall inside the writing of a row, a state or a JSON file.

Then, for every branch record of the uninterrupted run (each directory holding a branch.csv:
the cone, the branches with contact, the n-fold cones, the winding, ...):
  - its branch.csv must have the same rows, each value equal to 1e-8 (relative, with an
    absolute floor of 1e-12), except corrector_iterations (a resumed start is corrected
    again);
  - its events.json the same events at the same phi_e;
  - its states/ one state per row, no temporary, and each state equal to the uninterrupted
    run's byte for byte (a resumed trace takes the very steps of the one that was killed);
and results.json (the study's, and each record's own) the same numbers in every key, nested
ones included, except wall times (keys ending in "seconds"). Prints what differs and exits 1
if anything does. The econe_contact study of the ctest scene takes about half an hour with
ten kills on one thread (docs/verification.md, "Resuming a killed study").
"""

import argparse
import csv
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time

RELATIVE, ABSOLUTE = 1e-8, 1e-12


def recorded_rows(directory):
    """Rows of every branch.csv below `directory` written so far (partial lines count)."""
    rows = 0
    for root, _, files in os.walk(directory):
        if "branch.csv" in files:
            try:
                with open(os.path.join(root, "branch.csv"), "rb") as f:
                    rows += max(0, f.read().count(b"\n") - 1)
            except OSError:
                pass
    return rows


def run(growshell, scene, out, resume, kill_at_rows=None, then=0.0):
    """Runs the study; with kill_at_rows, kills it with SIGKILL `then` seconds after the
    records below `out` hold that many rows in all (if it still runs). Returns (return code,
    whether it was killed, wall time, the log)."""
    command = [growshell, "run", scene, "--out", out] + (["--resume"] if resume else [])
    log_path = out.rstrip("/") + ".log"
    started = time.monotonic()
    with open(log_path, "a+") as log:
        log.write(f"\n=== {' '.join(command)}\n")
        log.flush()
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        killed = False
        if kill_at_rows is not None:
            while process.poll() is None and recorded_rows(out) < kill_at_rows:
                time.sleep(0.01)
            time.sleep(then)
            if process.poll() is None:
                process.send_signal(signal.SIGKILL)
                killed = True
        process.wait()
        log.seek(0)
        text = log.read()
    return process.returncode, killed, time.monotonic() - started, text


def close(a, b):
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except (TypeError, ValueError):
        return False
    if x != x and y != y:  # both NaN
        return True
    return abs(x - y) <= RELATIVE * max(abs(x), abs(y)) + ABSOLUTE


def compare_json(a, b, where, failures):
    """Every number, string and flag of a in b at the same place (wall times left out)."""
    if isinstance(a, dict):
        if not isinstance(b, dict):
            failures.append(f"{where}: {b!r}, uninterrupted an object")
            return
        for key, value in a.items():
            if key.endswith("seconds"):
                continue
            if key not in b:
                failures.append(f"{where}.{key} missing, uninterrupted {value!r}")
                continue
            compare_json(value, b[key], f"{where}.{key}", failures)
    elif isinstance(a, list):
        if not isinstance(b, list) or len(a) != len(b):
            failures.append(f"{where}: {b!r}, uninterrupted {a!r}")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            compare_json(x, y, f"{where}[{i}]", failures)
    elif isinstance(a, float) or isinstance(b, float):
        if not close(a, b):
            failures.append(f"{where}: {b!r}, uninterrupted {a!r}")
    elif a != b:
        failures.append(f"{where}: {b!r}, uninterrupted {a!r}")


def records(directory):
    """The directories below `directory` (itself included) that hold a branch.csv."""
    found = []
    for root, _, files in os.walk(directory):
        if "branch.csv" in files:
            found.append(os.path.relpath(root, directory))
    return sorted(found)


def compare_record(reference, killed, name, failures):
    a_dir, b_dir = os.path.join(reference, name), os.path.join(killed, name)
    if not os.path.isfile(os.path.join(b_dir, "branch.csv")):
        failures.append(f"{name}: no branch.csv")
        return
    with open(os.path.join(a_dir, "branch.csv"), newline="") as f:
        a = list(csv.reader(f))
    with open(os.path.join(b_dir, "branch.csv"), newline="") as f:
        b = list(csv.reader(f))
    if a[0] != b[0]:
        failures.append(f"{name}/branch.csv columns differ: {b[0]}, uninterrupted {a[0]}")
        return
    if len(a) != len(b):
        failures.append(f"{name}/branch.csv has {len(b) - 1} rows, uninterrupted {len(a) - 1}")
    for i, (x, y) in enumerate(zip(a[1:], b[1:])):
        for column, p, q in zip(a[0], x, y):
            if column != "corrector_iterations" and not close(p, q):
                failures.append(f"{name}/branch.csv row {i + 1}, {column}: {q}, uninterrupted {p}")
    for file in ("events.json", "results.json"):
        if os.path.isfile(os.path.join(a_dir, file)):
            try:
                with open(os.path.join(a_dir, file)) as f:
                    ja = json.load(f)
                with open(os.path.join(b_dir, file)) as f:
                    jb = json.load(f)
            except (OSError, ValueError) as e:
                failures.append(f"{name}/{file}: {e}")
                continue
            compare_json(ja, jb, f"{name}/{file}", failures)
    states = os.path.join(b_dir, "states")
    if os.path.isdir(states):
        names = sorted(os.listdir(states))
        if len(names) != len(b) - 1 or any(not n.endswith(".state") for n in names):
            failures.append(f"{name}/states holds {len(names)} files for {len(b) - 1} rows: "
                            f"{[n for n in names if not n.endswith('.state')]}")
        differing = [n for n in names
                     if file_bytes(os.path.join(states, n)) !=
                     file_bytes(os.path.join(a_dir, "states", n))]
        if differing:
            failures.append(f"{name}/states: {len(differing)} of {len(names)} states differ from "
                            f"the uninterrupted run's, from {differing[0]} on")


def file_bytes(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("growshell")
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--kills", type=int, default=10)
    parser.add_argument("--seed", type=int, default=17)
    args = parser.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    reference = os.path.join(args.out, "uninterrupted")
    rc_reference, _, duration, log = run(args.growshell, args.scene, reference, resume=False)
    if rc_reference not in (0, 3):
        sys.exit(f"the uninterrupted run failed ({rc_reference}):\n{log}")

    killed_dir = os.path.join(args.out, "killed")
    total = recorded_rows(reference)
    row_time = duration / max(1, total)
    moments = random.Random(args.seed)
    # Each kill after the records hold a number of rows drawn over the whole study (sorted),
    # then a delay of up to three rows' time, so that some fall inside the writing of a row, a
    # state or a JSON file, and some in the work between rows (a skewed search, a relaxation,
    # an Ipopt check). A resumed run that lost a stage writes its rows again before the next
    # kill's count is reached.
    targets = sorted(moments.sample(range(1, total), min(args.kills, total - 1)))
    kills, failures, spent = [], [], 0.0
    for target in targets:
        resume = os.path.isdir(killed_dir)
        then = moments.uniform(0.0, 3.0 * row_time)
        rc, killed, wall, log = run(args.growshell, args.scene, killed_dir, resume,
                                    kill_at_rows=target, then=then)
        spent += wall
        if killed:
            # Where it was: the last stage line of this run's log.
            this_run = log[log.rfind("\n=== "):]
            stages = [line for line in this_run.splitlines() if line.startswith("# stage")]
            kills.append(f"row {target} + {then:.1f} s, {stages[-1][:60] if stages else 'before stage 1'}")
        elif rc != rc_reference:
            failures.append(f"a run ended with {rc}, uninterrupted {rc_reference}:\n{log[-3000:]}")
            break
    rc, _, wall, log = run(args.growshell, args.scene, killed_dir, resume=True)
    spent += wall
    if rc != rc_reference:
        failures.append(f"the last resume ended with {rc}, uninterrupted {rc_reference}")

    if not failures:
        names = records(reference)
        if records(killed_dir) != names:
            failures.append(f"records {records(killed_dir)}, uninterrupted {names}")
        for name in names:
            compare_record(reference, killed_dir, name, failures)
        try:
            with open(os.path.join(reference, "results.json")) as f:
                ja = json.load(f)
            with open(os.path.join(killed_dir, "results.json")) as f:
                jb = json.load(f)
            compare_json(ja, jb, "results.json", failures)
        except (OSError, ValueError) as e:
            failures.append(f"results.json: {e}")

    for f in failures[:50]:
        print("FAILED:", f)
    if len(failures) > 50:
        print(f"... and {len(failures) - 50} more")
    for k in kills:
        print("killed after", k)
    print(f"{len(kills)} kills; uninterrupted run {duration:.1f} s, "
          f"killed and resumed runs {spent:.1f} s in all; {len(records(reference))} records "
          f"compared")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
