"""Small helpers of the integration scripts that drive the tools: a clean scratch directory, running
a tool quietly, writing a JSON config."""
import json
import os
import shutil
import subprocess


def enter_scratch(tmp):
    """Makes tmp an empty directory and changes into it."""
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    os.chdir(tmp)


def tool_runner(bin_dir):
    """run(name, *args): the tool of bin_dir with -q, its output captured."""
    def run(name, *args):
        return subprocess.run([os.path.join(bin_dir, name), "-q", *args], capture_output=True, text=True)
    return run


def write(name, value):
    """Writes value as JSON to name and returns name."""
    json.dump(value, open(name, "w"))
    return name


def run(cmd):
    """Runs a command line to completion, its output captured as text."""
    return subprocess.run(cmd, capture_output=True, text=True)


def observable(f, name):
    """(values, times) of observable `name` of an open H5MD file, in /observables or /anisodyn/observables."""
    for group in ("observables", "anisodyn/observables"):
        if f"{group}/{name}" in f:
            return f[f"{group}/{name}/value"][...], f[f"{group}/{name}/time"][...]
    raise KeyError(name)


def expect_bad_input(what, cmd, names, output="bad.h5"):
    """Runs cmd, a tool given bad input: it must exit 2, name in its message every string of `names`
    (the JSON path; a tuple stands for one of its strings, e.g. the config file or the input file),
    and leave nothing at `output` or beside it. Prints the message's last line."""
    r = run(cmd)
    assert r.returncode == 2, (what, r.returncode, r.stderr)
    for name in names:
        alternatives = name if isinstance(name, tuple) else (name,)
        assert any(a in r.stderr for a in alternatives), (what, name, r.stderr)
    assert not any(f.startswith(output) for f in os.listdir(".")), what
    print(f"bad input, {what}: exit 2: {r.stderr.strip().splitlines()[-1][:160]}")
