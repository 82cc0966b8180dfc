"""Golden outputs: digests of every dataset a manifest run writes, recorded once and compared bit for
bit afterwards, so that a refactoring that must not change results (issue 14) is checked on every
smoke manifest and the quickstart.

A digest covers a dataset's dtype, shape and bytes (the first 16 hex digits of its SHA-256).
Datasets added since the record are listed, not failed; every recorded one must be unchanged.
Provenance is left out (it names the revision, the host and the time): datasets under a group
called `provenance`, and string datasets, which hold configuration text and paths. Attributes are
not compared. Species files (`*.species.json`, anisodyn-hydro) count too: each top-level entry but
`provenance`, as canonical JSON without the solve timings (`seconds`).

Bit-identical floating point needs the same compiler and the same instruction set: the build uses
-march=native. The digests are therefore stored with a fingerprint of the compiler and of the
target flags -march=native enables; on a machine with another fingerprint the comparison is
skipped and says so (the record command re-records for that machine).

Command line:
  golden_outputs.py record  RESULTS_DIR OUT.json     digests of every .h5 below RESULTS_DIR
  golden_outputs.py compare RESULTS_DIR GOLDEN.json  exit 1 on any difference
"""
import hashlib
import json
import os
import subprocess
import sys

import h5py
import numpy as np


def fingerprint():
    """Compiler version and the target flags -march=native turns on (what decides the code's rounding)."""
    cxx = os.environ.get("CXX", "c++")
    version = subprocess.run([cxx, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    flags = subprocess.run([cxx, "-march=native", "-Q", "--help=target"], capture_output=True, text=True).stdout
    enabled = sorted(line.split()[0] for line in flags.splitlines() if line.strip().endswith("[enabled]"))
    march = [line.split()[-1] for line in flags.splitlines() if line.strip().startswith("-march=")]
    return {"compiler": version, "march": march[0] if march else "?",
            "target_flags_sha256": hashlib.sha256("\n".join(enabled).encode()).hexdigest()}


def _skipped(name, obj):
    return "provenance" in name.split("/") or obj.dtype.kind in ("S", "U", "O")


def file_digests(path):
    """{dataset path: sha256 of dtype, shape and bytes} for one HDF5 file."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and not _skipped(name, obj):
                a = np.ascontiguousarray(obj[()])
                h = hashlib.sha256(f"{a.dtype.str}{a.shape}".encode())
                h.update(a.tobytes())
                out[name] = h.hexdigest()[:16]
        f.visititems(visit)
    return out


TIMINGS = {"seconds"}  # keys holding measured run times, which no two runs share


def _without_timings(value):
    if isinstance(value, dict):
        return {k: _without_timings(v) for k, v in value.items() if k not in TIMINGS}
    if isinstance(value, list):
        return [_without_timings(v) for v in value]
    return value


def species_file_digests(path):
    """{top-level key: digest of its canonical JSON} for a species file, provenance and timings left out."""
    data = json.load(open(path))
    return {key: hashlib.sha256(json.dumps(_without_timings(value), sort_keys=True).encode()).hexdigest()[:16]
            for key, value in data.items() if key != "provenance"}


def tree_digests(results_dir):
    """Digests of every .h5 and species file below results_dir, keyed by its path relative to it."""
    out = {}
    for root, _, files in os.walk(results_dir):
        for name in sorted(files):
            path = os.path.join(root, name)
            if name.endswith(".h5") and ".checkpoint" not in name:
                out[os.path.relpath(path, results_dir)] = file_digests(path)
            elif name.endswith(".species.json"):
                out[os.path.relpath(path, results_dir)] = species_file_digests(path)
    return dict(sorted(out.items()))


def record(results_dir, out_path):
    data = {"fingerprint": fingerprint(), "files": tree_digests(results_dir)}
    tmp = out_path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(tmp, out_path)
    return data


def compare(results_dir, golden_path):
    """(problems, note): problems is a list of differences (empty when identical); note says what was compared or why not."""
    golden = json.load(open(golden_path))
    here = fingerprint()
    if here != golden["fingerprint"]:
        return [], (f"golden outputs not compared: recorded with {golden['fingerprint']['compiler']} "
                    f"/ {golden['fingerprint']['march']}, this machine is {here['compiler']} / {here['march']} "
                    f"(other target flags: {here['target_flags_sha256'] != golden['fingerprint']['target_flags_sha256']})")
    # Only the studies the record holds: a results folder may hold other manifests' runs too.
    studies = {rel.split(os.sep)[0] for rel in golden["files"]}
    now = {rel: d for rel, d in tree_digests(results_dir).items() if rel.split(os.sep)[0] in studies}
    # Every recorded dataset must be there with the same bits. Datasets a later version adds
    # (new outputs, e.g. anisodyn-msd's D0 scalars) are listed, not failed: they change nothing
    # that was there before.
    problems, added = [], []
    for rel in sorted(set(golden["files"]) | set(now)):
        if rel not in now:
            problems.append(f"{rel}: missing")
            continue
        if rel not in golden["files"]:
            problems.append(f"{rel}: not in the golden record")
            continue
        want, got = golden["files"][rel], now[rel]
        for name in sorted(set(want) | set(got)):
            if name not in want:
                added.append(f"{rel}:/{name}")
            elif want.get(name) != got.get(name):
                problems.append(f"{rel}:/{name} {'missing' if name not in got else 'differs'}")
    compared = sum(len(v) for v in golden["files"].values())
    note = f"golden outputs: {len(now)} files, {compared} recorded datasets compared bit for bit"
    if added:
        note += f"; {len(added)} datasets added since the record (not compared): " + ", ".join(added[:6]) + (" …" if len(added) > 6 else "")
    return problems, note


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("record", "compare"):
        sys.exit(__doc__)
    if sys.argv[1] == "record":
        d = record(sys.argv[2], sys.argv[3])
        print(f"recorded {len(d['files'])} files into {sys.argv[3]}")
    else:
        problems, note = compare(sys.argv[2], sys.argv[3])
        print(note)
        for p in problems:
            print("  " + p)
        sys.exit(1 if problems else 0)
