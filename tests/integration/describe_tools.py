#!/usr/bin/env python3
"""Every executable describes itself, and the runner goes by the descriptions (docs/manifests.md,
"Tool descriptions"):
  1. each executable of engine/apps and analysis/apps answers `--describe` alone with exit 0 and one
     JSON object on stdout (nothing on stderr): name, role, replica, inputs, output, parameters
     (name, type, required, default unless required, meaning; no name twice) and cost, as the
     runner's own check (describe.check) accepts them; `anisodyn TOOL --describe` gives the same;
  2. every engine states a cost model, every other tool a kind without estimate;
  3. every top-level key of every stage's params and of every defaults block in manifests/*.json
     and manifests/validation/*.json is a described parameter of its tool;
  4. with a fake tool directory (the real executables plus a scripted anisodyn-toyengine),
     `anisodyn-run --dry-run` refuses an engine whose description has no cost model (exit 3, naming
     the tool) or lacks a field, and estimates an engine that states a model of its own
     (particles × steps at its rate) with no change to the runner, asking the tool once.
argv: [1] build bin dir, [2] scratch dir, [3] source dir."""
import glob
import json
import os
import shutil
import subprocess
import sys

bin_dir, tmp, source = (os.path.abspath(a) for a in sys.argv[1:4])
sys.path.insert(0, os.path.join(source, "workflows"))
from anisodyn_run.describe import DescriptionError, check  # noqa: E402

shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
failures = []


def expect(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


# 1, 2. every executable
apps = sorted(os.path.splitext(os.path.basename(p))[0]
              for p in glob.glob(os.path.join(source, "engine", "apps", "*.cpp")) + glob.glob(os.path.join(source, "analysis", "apps", "*.cpp")))
expect(len(apps) >= 14, f"{len(apps)} executables in engine/apps and analysis/apps")
descriptions = {}
for app in apps:
    r = subprocess.run([os.path.join(bin_dir, app), "--describe"], capture_output=True, text=True, cwd=tmp, timeout=60)
    try:
        d = json.loads(r.stdout)
    except json.JSONDecodeError as e:
        expect(False, f"{app} --describe prints JSON ({e}; exit {r.returncode}, stderr {r.stderr.strip()[:120]})")
        continue
    expect(r.returncode == 0 and not r.stderr and not os.listdir(tmp), f"{app} --describe: exit 0, nothing on stderr, no file written")
    try:
        check(d, app)
        ok = True
    except DescriptionError as e:
        ok = False
        print(f"     {e}")
    names = [p["name"] for p in d.get("parameters", [])]
    expect(ok and d["name"] == app and len(names) == len(set(names)),
           f"{app}: role {d.get('role')}, replica {d.get('replica')}, {len(names)} distinct parameters, cost {d.get('cost', {}).get('kind')}")
    kind = d.get("cost", {}).get("kind")
    expect((kind == "model") == (d.get("role") == "engine"), f"{app}: {'an engine with a cost model' if kind == 'model' else 'no estimate: ' + str(d.get('cost', {}).get('why'))}")
    descriptions[app] = d
    if app.startswith("anisodyn-"):
        via = subprocess.run([os.path.join(bin_dir, "anisodyn"), app[len("anisodyn-"):], "--describe"], capture_output=True, text=True, timeout=60)
        expect(via.returncode == 0 and json.loads(via.stdout) == d, f"anisodyn {app[len('anisodyn-'):]} --describe is the same")
engines = sorted(a for a, d in descriptions.items() if d["role"] == "engine")
expect(engines == ["anisodyn-bd", "anisodyn-dmc", "anisodyn-dpd", "anisodyn-lb", "anisodyn-mc"], f"the engines: {', '.join(engines)}")
expect(all(descriptions[a]["replica"] for a in ("anisodyn-config", "anisodyn-mc", "anisodyn-dmc", "anisodyn-bd", "anisodyn-dpd", "anisodyn-lb")) and
       not any(d["replica"] for a, d in descriptions.items() if d["role"] in ("analysis", "tensors")),
       "builder and engines take --replica; analysis and hydro do not")

# 3. the manifests' keys are described parameters
manifests = sorted(glob.glob(os.path.join(source, "manifests", "*.json")) + glob.glob(os.path.join(source, "manifests", "validation", "*.json")))
checked, unknown = 0, []
for path in manifests:
    m = json.load(open(path))
    blocks = [(f"stages[{i}].params", st["tool"], st.get("params", {})) for i, st in enumerate(m["stages"])]
    blocks += [(f"defaults.{tool}", tool, params) for tool, params in m.get("defaults", {}).items()]
    for where, tool, params in blocks:
        described = {p["name"] for p in descriptions[f"anisodyn-{tool}"]["parameters"]}
        for key in params:
            checked += 1
            if not key.startswith("_") and key not in described:
                unknown.append(f"{os.path.relpath(path, source)}: {where}.{key} is not a parameter of anisodyn-{tool}")
for u in unknown:
    print(f"     {u}")
expect(not unknown, f"{checked} top-level keys of {len(manifests)} manifests are described parameters of their tools")

# 4. the runner with a fake tool directory
fake = os.path.join(tmp, "bin")
os.makedirs(fake)
for app in apps:
    os.symlink(os.path.join(os.path.abspath(bin_dir), app), os.path.join(fake, app))
calls = os.path.join(tmp, "toyengine.calls")
TOY = {"name": "anisodyn-toyengine", "summary": "a scripted engine", "role": "engine", "replica": True,
       "inputs": {"kind": "state", "min": 1, "max": 1, "meaning": "the start"},
       "output": {"kind": "trajectory", "format": "H5MD", "meaning": "frames"},
       "parameters": [{"name": "steps", "type": "integer", "required": True, "meaning": "run length"}]}


def toy(description):
    path = os.path.join(fake, "anisodyn-toyengine")
    with open(path, "w") as f:
        f.write(f"#!/bin/sh\necho called >> '{calls}'\ncat <<'JSON'\n{json.dumps(description)}\nJSON\n")
    os.chmod(path, 0o755)
    if os.path.exists(calls):
        os.remove(calls)


MANIFEST = {"study": "toy", "replicas": 2, "grid": {"n": [100, 300]}, "stages": [
    {"name": "config", "tool": "config",
     "params": {"species": [{"name": "s", "shape": {"type": "sphere", "diameter": 1.0}}],
                "composition": [{"species": "s", "count": "${grid.n}"}], "box": {"packing_fraction": 0.1}}},
    {"name": "run", "tool": "toyengine", "inputs": ["config"], "params": {"steps": 5000}},
    {"name": "msd", "tool": "msd", "inputs": ["run"]}]}
manifest = os.path.join(tmp, "toy.json")
json.dump(MANIFEST, open(manifest, "w"))


def dry_run():
    return subprocess.run([sys.executable, os.path.join(source, "workflows", "anisodyn-run"), manifest, "--bin", fake, "--dry-run",
                           "--results", os.path.join(tmp, "results")], capture_output=True, text=True, timeout=120)


toy(dict(TOY, cost={"kind": "negligible", "why": "none given"}))
r = dry_run()
expect(r.returncode == 3 and "anisodyn-toyengine" in r.stderr and "cost model" in r.stderr and "total:" not in r.stdout,
       f"an engine without a cost model: exit {r.returncode}, {r.stderr.strip()}")
toy({k: v for k, v in TOY.items() if k != "replica"} | {"cost": {"kind": "negligible", "why": "-"}})
r = dry_run()
expect(r.returncode == 3 and "anisodyn-toyengine" in r.stderr and "'replica'" in r.stderr, f"a description without 'replica': {r.stderr.strip()}")

toy(dict(TOY, cost={"kind": "model", "work": "particle steps", "amount": ["particles", {"param": "steps"}], "rate": 1e6,
                    "measured": "made up for the test"}))
r = dry_run()
rows = {line.split()[0]: line for line in r.stdout.splitlines() if line.strip()}
# 2 grid points x 2 replicas: 2 x (100 + 300 particles) x 5000 steps = 4e6 particle steps, 4 s at 1e6/s
expect(r.returncode == 0 and rows.get("run", "").split()[2:3] == ["4"] and rows["run"].split()[-3:] == ["4.00e6", "4", "s"]
       and "particle steps" in rows.get("stage", "") and "toyengine 1e+06/s" in rows.get("total:", ""),
       f"an engine's own model (particles x steps at its rate, replicated by default) is estimated: {rows.get('run')}")
expect(open(calls).read().count("called") == 1, "the runner asked the tool for its description once")

print(f"{len(failures)} failed")
assert not failures, f"{len(failures)} check(s) failed: {failures}"
