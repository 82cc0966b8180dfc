"""Checks shared by the engines' pipeline tests: interrupt a run (SIGINT, or SIGKILL after a
periodic checkpoint), resume it, and compare its output with the uninterrupted run's, bit for bit
(every frame element with its steps and times, every observable with its steps, times and values).
"""
import os
import signal
import subprocess
import time

import h5py
import numpy as np


def compare_outputs(a, b):
    """Asserts that two H5MD outputs hold the same frames and observables; returns (elements, observables) compared."""
    with h5py.File(a) as fa, h5py.File(b) as fb:
        elements = sorted(fa["particles/all"].keys())
        assert elements == sorted(fb["particles/all"].keys()), (elements, sorted(fb["particles/all"].keys()))
        for e in elements:
            for part in (["edges/value"] if e == "box" else ["value", "step", "time"]):
                key = f"particles/all/{e}/{part}"
                assert np.array_equal(fa[key][...], fb[key][...]), f"{key} differs between {a} and {b}"
        count = 0
        for group in ("observables", "anisodyn/observables"):
            names = set(fa[group].keys()) if group in fa else set()
            assert names == (set(fb[group].keys()) if group in fb else set()), group
            for n in names:
                for part in ("step", "time", "value"):
                    assert np.array_equal(fa[f"{group}/{n}/{part}"][...], fb[f"{group}/{n}/{part}"][...], equal_nan=True), \
                        f"{group}/{n}/{part} differs between {a} and {b}"
            count += len(names)
        return len(elements), count


def interrupted(cmd, sig, delay):
    """Starts cmd, sends `sig` after `delay` seconds; returns (exit code, stderr)."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    p.send_signal(sig)
    _, err = p.communicate()
    return p.returncode, err


def killed_after_checkpoint(cmd, checkpoint, delay, timeout=60):
    """Starts cmd and SIGKILLs it `delay` seconds after its first periodic checkpoint appeared."""
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + timeout
    while not os.path.exists(checkpoint) and time.time() < deadline and p.poll() is None:
        time.sleep(0.005)
    time.sleep(delay)
    p.kill()
    p.wait()
    assert os.path.exists(checkpoint), "no periodic checkpoint before SIGKILL"


def check_resumes(cmd_for, output_prefix, reference, duration, run):
    """The SIGINT and SIGKILL resume checks of one engine command: cmd_for(out) gives the command
    line writing `out`; `reference` is the uninterrupted output and `duration` its run time;
    run(cmd) runs a command to completion. Returns the summaries (JSON text) of the two resumed runs."""
    delay = max(0.05, min(1.0, duration / 3))
    out = f"{output_prefix}_sigint.h5"
    code, err = interrupted(cmd_for(out), signal.SIGINT, delay)
    assert code == 130, f"SIGINT: exit code {code}, expected 130 ({err})"
    assert os.path.exists(out + ".checkpoint.h5") and not os.path.exists(out), "SIGINT must leave a checkpoint and no output"
    r = run(cmd_for(out))
    assert r.returncode == 0, r.stderr
    assert not os.path.exists(out + ".checkpoint.h5"), "the checkpoint must be removed after completion"
    ne, no = compare_outputs(reference, out)
    print(f"SIGINT after {delay:.2f} s -> exit 130, resumed: identical ({ne} particle elements, {no} observables)")
    summaries = [r.stdout]
    out = f"{output_prefix}_killed.h5"
    killed_after_checkpoint(cmd_for(out), out + ".checkpoint.h5", delay / 2)
    r = run(cmd_for(out))
    assert r.returncode == 0, r.stderr
    compare_outputs(reference, out)
    print("SIGKILL after a periodic checkpoint, resumed: identical")
    return summaries + [r.stdout]
