#!/usr/bin/env python3
"""anisodyn-run refuses bad manifests before any job runs: exit 2, a message naming the manifest
file and the JSON path, and no campaign directory (nothing written)."""
import copy
import json
import os
import shutil
import subprocess
import sys

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
runner = [sys.executable, os.path.join(source, "workflows", "anisodyn-run"), "--bin", bin_dir]

GOOD = {
    "study": "bad",
    "grid": {"eta": [0.05, 0.1]},
    "replicas": 2,
    "stages": [
        {"name": "config", "tool": "config", "params": {"species": [{"name": "s", "shape": {"type": "sphere", "diameter": 1}}],
                                                        "composition": [{"species": "s", "count": 10}],
                                                        "box": {"packing_fraction": "${grid.eta}"}}},
        {"name": "msd", "tool": "msd", "inputs": ["config"], "params": {}},
    ],
}


def case(label, mutate, path_fragment):
    m = copy.deepcopy(GOOD)
    mutate(m)
    return label, m, path_fragment


def unknown_tool(m): m["stages"][1]["tool"] = "nosuchtool"
def bad_reference(m): m["stages"][0]["params"]["box"]["packing_fraction"] = "${grid.phi}"
def empty_grid(m): m["grid"]["eta"] = []
def zero_replicas(m): m["replicas"] = 0
def negative_replicas(m): m["replicas"] = -3
def unknown_input(m): m["stages"][1]["inputs"] = ["cfg"]
def unknown_key(m): m["stagez"] = []
def replica_outside(m): m["stages"][1]["params"]["label"] = "${replica}"
def bad_zip(m): m["grid"]["W"] = [1, 2, 3]; m["zip"] = [["eta", "W"]]


def cycle(m):
    m["stages"][0]["inputs"] = ["msd"]


cases = [
    case("unknown tool", unknown_tool, "stages[1].tool"),
    case("reference to no grid variable", bad_reference, "stages[0].params.box.packing_fraction"),
    case("cycle in stage inputs", cycle, "stages[0].inputs"),
    case("grid with an empty list", empty_grid, "grid.eta"),
    case("replicas = 0", zero_replicas, "replicas"),
    case("replicas < 0", negative_replicas, "replicas"),
    case("input that is no stage", unknown_input, "stages[1].inputs[0]"),
    case("unknown top-level key", unknown_key, "stagez"),
    case("${replica} in a stage that is not replicated", replica_outside, "stages[1].params.label"),
    case("zip of lists of different lengths", bad_zip, "zip[0][1]"),
]
failures = 0
for label, manifest, fragment in cases:
    path = os.path.join(tmp, "manifest.json")
    with open(path, "w") as f:
        json.dump(manifest, f)
    results = os.path.join(tmp, "results")
    r = subprocess.run(runner + ["--results", results, path], capture_output=True, text=True)
    problems = []
    if r.returncode != 2:
        problems.append(f"exit {r.returncode}, expected 2")
    if path not in r.stderr:
        problems.append("message does not name the manifest file")
    if f"at {fragment}" not in r.stderr:
        problems.append(f"message does not name the JSON path {fragment}")
    if os.path.exists(results):
        problems.append("something was written")
    print(f"{'ok  ' if not problems else 'FAIL'} {label}: {r.stderr.strip()}" + (f" -- {'; '.join(problems)}" if problems else ""))
    failures += bool(problems)
    shutil.rmtree(results, ignore_errors=True)

# invalid JSON and a missing file
for label, text, expect in (("invalid JSON", "{\"study\": ", "line 1"), ("missing file", None, "readable manifest")):
    path = os.path.join(tmp, "broken.json")
    if text is None:
        path = os.path.join(tmp, "does-not-exist.json")
    else:
        open(path, "w").write(text)
    r = subprocess.run(runner + ["--results", os.path.join(tmp, "results"), path], capture_output=True, text=True)
    ok = r.returncode == 2 and expect in r.stderr and not os.path.exists(os.path.join(tmp, "results"))
    print(f"{'ok  ' if ok else 'FAIL'} {label}: {r.stderr.strip()}")
    failures += not ok

# the good manifest passes validation (a dry run writes nothing either)
path = os.path.join(tmp, "good.json")
json.dump(GOOD, open(path, "w"))
r = subprocess.run(runner + ["--results", os.path.join(tmp, "results"), "--dry-run", path], capture_output=True, text=True)
ok = r.returncode == 0 and "-> 6 jobs" in r.stdout and not os.path.exists(os.path.join(tmp, "results"))
print(f"{'ok  ' if ok else 'FAIL'} the good manifest: dry run exit {r.returncode}: {r.stdout.splitlines()[0] if r.stdout else r.stderr}")
failures += not ok
print(f"{failures} failed")
assert failures == 0, f"{failures} bad-manifest case(s) failed (see above)"
