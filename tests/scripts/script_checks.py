"""What the tests of scripts/ share: running one of the scripts as the user would, and
collecting the checks that failed, so that a test reports all of them before it exits."""

import os
import subprocess
import sys

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")


def run_script(name, *args):
    """Runs scripts/NAME with ARGS under this Python; returns the CompletedProcess (text)."""
    return subprocess.run([sys.executable, os.path.join(SCRIPTS, name)] + list(args),
                          capture_output=True, text=True)


class Checks:
    """check(condition, what) records `what` when condition is false; finish() prints every
    failure and exits 1 if there was one, else 0."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, what):
        if not condition:
            self.failures.append(what)

    def finish(self):
        for f in self.failures:
            print("FAILED:", f)
        sys.exit(1 if self.failures else 0)
