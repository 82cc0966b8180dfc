"""The ok/FAIL lines of an integration script: check(cond, what) prints one line per check and keeps
the failures; finish() prints their count and fails (an assertion, exit 1) if there were any."""
import sys

failures = []


def check(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


def finish():
    print(f"{len(failures)} failed")
    assert not failures, f"{len(failures)} check(s) failed: {failures}"
    sys.exit(0)
