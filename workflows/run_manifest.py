#!/usr/bin/env python3
"""Minimal manifest runner: executes a manifest's stages in order, one replica, no grid.

This is the seed of `anisodyn-run` (workflows issue): it already validates the manifest with
errors that name the JSON path, writes each stage's parameters next to its output, skips a stage
whose output exists and whose parameters and inputs are unchanged, and exits 2 on bad input.

Manifest (architecture §6):
  {"study": "name", "description": "...", "defaults": {...},
   "stages": [{"name": "config", "tool": "config", "params": {...}},
              {"name": "equilibrate", "tool": "mc", "inputs": ["config"], "params": {...}}]}
Each stage runs `anisodyn-<tool> --config <study>/<stage>.json --input <inputs' outputs>
--output <study>/<stage>.h5`. `defaults` are merged under every stage's params.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import time


class ManifestError(Exception):
    pass


def fail(path, expected, got=None):
    msg = f"at {path}: expected {expected}"
    if got is not None:
        msg += f", got {json.dumps(got)[:60]}"
    raise ManifestError(msg)


def merge(base, over):
    out = dict(base)
    for k, v in over.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def validate(m, bin_dir):
    if not isinstance(m, dict):
        fail("(top level)", "a JSON object", m)
    known = {"study", "description", "defaults", "grid", "replicas", "stages", "report"}
    for k in m:
        if k not in known and not k.startswith("_"):
            fail(k, "one of " + ", ".join(sorted(known)) + " (unknown key)")
    if not isinstance(m.get("study"), str) or not m["study"]:
        fail("study", "a non-empty study name", m.get("study"))
    if m.get("grid") not in (None, {}):
        fail("grid", "no grid: grids need anisodyn-run (not yet available)", m.get("grid"))
    if m.get("replicas", 1) != 1:
        fail("replicas", "1: replicas need anisodyn-run (not yet available)", m.get("replicas"))
    stages = m.get("stages")
    if not isinstance(stages, list) or not stages:
        fail("stages", "a non-empty array of stages", stages)
    seen = set()
    for i, st in enumerate(stages):
        p = f"stages[{i}]"
        if not isinstance(st, dict):
            fail(p, "an object", st)
        for k in st:
            if k not in {"name", "tool", "params", "inputs", "description", "output"}:
                fail(f"{p}.{k}", "one of name, tool, params, inputs, description, output (unknown key)")
        out = st.get("output", "x.h5")
        if not isinstance(out, str) or not out or os.sep in out or out.startswith("."):
            fail(f"{p}.output", "a plain file name for the stage's output (default <name>.h5)", out)
        if not isinstance(st.get("name"), str) or not st["name"]:
            fail(f"{p}.name", "a stage name", st.get("name"))
        if st["name"] in seen:
            fail(f"{p}.name", "a unique stage name", st["name"])
        tool = st.get("tool")
        if not isinstance(tool, str) or not os.access(os.path.join(bin_dir, f"anisodyn-{tool}"), os.X_OK):
            fail(f"{p}.tool", "the name of an anisodyn tool (anisodyn-<tool> in " + bin_dir + ")", tool)
        for j, inp in enumerate(st.get("inputs", [])):
            if inp not in seen:
                fail(f"{p}.inputs[{j}]", "the name of an earlier stage", inp)
        if not isinstance(st.get("params", {}), dict):
            fail(f"{p}.params", "an object", st.get("params"))
        seen.add(st["name"])


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("manifest")
    ap.add_argument("--bin", required=True, help="directory of the anisodyn executables")
    ap.add_argument("--results", required=True, help="results directory")
    ap.add_argument("--force", action="store_true", help="re-run every stage")
    args = ap.parse_args()
    try:
        with open(args.manifest) as f:
            manifest = json.load(f)
    except OSError as e:
        print(f"anisodyn-run: error: {args.manifest}: cannot open file: {e.strerror}", file=sys.stderr)
        return 2
    except json.JSONDecodeError as e:
        print(f"anisodyn-run: error: {args.manifest}: invalid JSON at line {e.lineno}, column {e.colno}: {e.msg}", file=sys.stderr)
        return 2
    try:
        validate(manifest, args.bin)
    except ManifestError as e:
        print(f"anisodyn-run: error: {args.manifest}: {e}", file=sys.stderr)
        return 2

    # Tools run in the repository root, so data paths in manifests ("manifests/data/…") resolve the
    # same wherever the runner is started; every path handed to them is absolute.
    repo_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    args.bin = os.path.abspath(args.bin)
    out_dir = os.path.abspath(os.path.join(args.results, manifest["study"]))
    os.makedirs(out_dir, exist_ok=True)
    outputs = {}
    t_start = time.time()
    stages = manifest["stages"]
    for k, st in enumerate(stages, 1):
        name = st["name"]
        params = merge(manifest.get("defaults", {}), st.get("params", {}))
        cfg_path = os.path.join(out_dir, f"{name}.json")
        out_path = os.path.join(out_dir, st.get("output", f"{name}.h5"))
        inputs = [outputs[i] for i in st.get("inputs", [])]
        stamp = {"tool": st["tool"], "params": params, "inputs": {p: sha256(p) for p in inputs}}
        stamp_path = os.path.join(out_dir, f".{name}.stamp.json")
        if not args.force and os.path.exists(out_path) and os.path.exists(stamp_path):
            with open(stamp_path) as f:
                if json.load(f) == stamp:
                    print(f"[{k}/{len(stages)}] {name}: up to date ({out_path})", file=sys.stderr)
                    outputs[name] = out_path
                    continue
        with open(cfg_path, "w") as f:
            json.dump(params, f, indent=2)
        cmd = [os.path.join(args.bin, f"anisodyn-{st['tool']}"), "--config", cfg_path, "--output", out_path]
        for p in inputs:
            cmd += ["--input", p]
        print(f"[{k}/{len(stages)}] {name}: {' '.join(cmd)}", file=sys.stderr)
        t0 = time.time()
        with open(os.path.join(out_dir, f"{name}.log"), "w") as log:
            rc = subprocess.call(cmd, stdout=log, cwd=repo_root)
        if rc != 0:
            print(f"anisodyn-run: stage '{name}' failed with exit code {rc} (stdout in {out_dir}/{name}.log)", file=sys.stderr)
            return rc
        with open(stamp_path, "w") as f:
            json.dump(stamp, f)
        outputs[name] = out_path
        print(f"[{k}/{len(stages)}] {name}: done in {time.time() - t0:.1f} s", file=sys.stderr)
    print(f"{manifest['study']}: {len(stages)} stages done in {time.time() - t_start:.1f} s; results in {out_dir}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
