"""The ok/FAIL lines of an integration script: check(cond, what) prints one line per check and keeps
the failures; finish() prints their count and returns them, for the script's own assertion."""
failures = []


def check(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


def finish():
    print(f"{len(failures)} failed")
    return list(failures)
