"""The tools' descriptions: every anisodyn executable answers `--describe` with JSON saying what it
is (role), whether it takes --replica (then campaigns replicate it by default), what it reads and
writes, its top-level configuration keys and, for an engine, its cost model (docs/manifests.md,
"Tool descriptions"). The runner asks each tool a manifest uses once per run and keeps the answer;
it has no list of tools of its own."""
import json
import os
import subprocess

from . import cost

ROLES = {"builder", "engine", "analysis", "tensors", "example", "dispatcher"}
OUTPUT_KINDS = {"none", "state", "trajectory", "species", "analysis"}
INPUT_KINDS = {"none", "state", "trajectory"}
FIELDS = ("name", "role", "replica", "inputs", "output", "parameters", "cost")


class DescriptionError(Exception):
    """A tool that does not describe itself, or whose description lacks what the runner needs."""


class Tools:
    """The executables bin_dir/anisodyn-<tool> and their descriptions (each asked at most once)."""

    def __init__(self, bin_dir):
        self.bin_dir = bin_dir
        self.known = {}

    def path(self, tool):
        return os.path.join(self.bin_dir, f"anisodyn-{tool}")

    def exists(self, tool):
        return os.path.isfile(self.path(tool)) and os.access(self.path(tool), os.X_OK)

    def describe(self, tool):
        """The checked description of anisodyn-<tool>; DescriptionError names the tool."""
        if tool not in self.known:
            exe = self.path(tool)
            try:
                done = subprocess.run([exe, "--describe"], capture_output=True, text=True, timeout=60)
            except (OSError, subprocess.TimeoutExpired) as e:
                raise DescriptionError(f"{exe} --describe: {e}")
            if done.returncode != 0:
                raise DescriptionError(f"{exe} --describe: exit {done.returncode}: {done.stderr.strip()[:200]}")
            try:
                d = json.loads(done.stdout)
            except json.JSONDecodeError as e:
                raise DescriptionError(f"{exe} --describe: not JSON ({e})")
            check(d, f"anisodyn-{tool}")
            self.known[tool] = d
        return self.known[tool]


def check(d, name):
    """What the runner relies on: the fields, their kinds, and a cost model for every engine."""
    def fail(what):
        raise DescriptionError(f"{name} --describe: {what}")

    if not isinstance(d, dict):
        fail("expected a JSON object")
    for k in FIELDS:
        if k not in d:
            fail(f"no '{k}' (a description has {', '.join(FIELDS)})")
    if d["role"] not in ROLES:
        fail(f"role '{d['role']}' is none of {', '.join(sorted(ROLES))}")
    if not isinstance(d["replica"], bool):
        fail("'replica' must be true or false")
    ins, out = d["inputs"], d["output"]
    if not isinstance(ins, dict) or ins.get("kind") not in INPUT_KINDS or not isinstance(ins.get("min"), int) \
            or not (ins.get("max") is None or isinstance(ins.get("max"), int)):
        fail(f"'inputs' must be {{kind: {' | '.join(sorted(INPUT_KINDS))}, min, max (null: any number)}}")
    if not isinstance(out, dict) or out.get("kind") not in OUTPUT_KINDS:
        fail(f"'output' must be {{kind: {' | '.join(sorted(OUTPUT_KINDS))}, format, meaning}}")
    if not isinstance(d["parameters"], list):
        fail("'parameters' must be a list")
    for i, p in enumerate(d["parameters"]):
        if not isinstance(p, dict) or not all(isinstance(p.get(k), str) and p.get(k) for k in ("name", "type", "meaning")) \
                or not isinstance(p.get("required"), bool) or (not p["required"] and "default" not in p):
            fail(f"parameters[{i}] must be {{name, type, required, default (unless required), meaning}}")
    try:
        cost.check_model(d["cost"], d["role"] == "engine")
    except ValueError as e:
        fail(str(e))
