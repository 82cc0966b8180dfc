"""Expansion of a validated manifest into jobs: one per (stage, grid point the stage depends on,
replica if the stage is replicated).

A stage depends on the grid variables its parameters reference and on those of its inputs, so a
stage that ignores a variable runs once for all its values. A job's id is a hash of its tool,
its substituted parameters, its replica index and the ids of its input jobs; two grid points that
give the same job share it.

Inputs: a replicated stage reading a replicated stage takes the same replica; a stage that is not
replicated reading a replicated one takes every replica (that is how analysis stages aggregate).
Files: <results>/<study>/<stage>/<var>=<value>/.../<stage>[-r<K>].h5, with .json (the stage
configuration), .log (stdout) and .err (stderr) beside it.
"""
import hashlib
import itertools
import json
import os
from dataclasses import dataclass, field

from .manifest import format_value, merge, referenced_vars, replicated, substitute


@dataclass
class Job:
    id: str
    stage: str
    tool: str
    params: dict
    point: dict                  # the grid values this job depends on (in grid order)
    replica: object              # int, or None for a stage that is not replicated
    inputs: list                 # ids of input jobs, in the order of the stage's inputs
    directory: str               # relative to the campaign directory
    stem: str                    # <stage>[-r<K>]: the configuration, logs and stamp are <stem>.json, ...
    filename: str                # the output: <stem>.h5, or the stage's "output" name (-r<K> before its first dot)
    downstream: list = field(default_factory=list)
    info: dict = field(default_factory=dict, repr=False, compare=False)  # the tool's description (describe.py)

    @property
    def output(self):
        return os.path.join(self.directory, self.filename)

    @property
    def config(self):
        return os.path.join(self.directory, self.stem + ".json")

    @property
    def log(self):
        return os.path.join(self.directory, self.stem + ".log")

    @property
    def err(self):
        return os.path.join(self.directory, self.stem + ".err")

    @property
    def label(self):
        where = ",".join(f"{k}={format_value(v)}" for k, v in self.point.items())
        rep = "" if self.replica is None else f" r{self.replica}"
        return f"{self.stage}[{where}]{rep}" if where else f"{self.stage}{rep}"


def grid_points(m):
    """Every grid point as an ordered dict var -> value (zip groups vary together)."""
    grid = m.get("grid", {})
    groups, grouped = [], set()
    for group in m.get("zip", []):
        groups.append(group)
        grouped.update(group)
    axes = []
    for var in grid:  # keep the manifest's order of variables
        if var in grouped:
            group = next(g for g in groups if g[0] == var) if any(g[0] == var for g in groups) else None
            if group:
                axes.append([{v: grid[v][i] for v in group} for i in range(len(grid[var]))])
        else:
            axes.append([{var: value} for value in grid[var]])
    points = []
    for combo in itertools.product(*axes):
        p = {}
        for part in combo:
            p.update(part)
        points.append({var: p[var] for var in grid})
    return points


def stage_vars(m, order):
    """The grid variables each stage depends on, in grid order."""
    stages, grid = m["stages"], list(m.get("grid", {}))
    index = {st["name"]: i for i, st in enumerate(stages)}
    deps = {}
    for i in order:
        st = stages[i]
        params = merge(m.get("defaults", {}).get(st["tool"], {}), st.get("params", {}))
        used = referenced_vars(params)
        for inp in st.get("inputs", []):
            used |= deps[index[inp]]
        deps[i] = used
    return {stages[i]["name"]: [v for v in grid if v in deps[i]] for i in deps}


def job_id(tool, params, replica, input_ids):
    text = json.dumps({"tool": tool, "params": params, "replica": replica, "inputs": input_ids}, sort_keys=True,
                      separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def output_name(stage, replica):
    if "output" not in stage:
        return (stage["name"] if replica is None else f"{stage['name']}-r{replica}") + ".h5"
    base, dot, ext = stage["output"].partition(".")
    return stage["output"] if replica is None else f"{base}-r{replica}{dot}{ext}"


def expand(m, order, tools):
    """All jobs, keyed by id, in an order where inputs come first; the job ids of each stage; and the
    grid variables each stage depends on. Each job carries its tool's description (`tools`)."""
    stages = m["stages"]
    stage_by_name = {st["name"]: st for st in stages}
    replicas = m.get("replicas", 1)
    deps = stage_vars(m, order)
    jobs, by_stage = {}, {}
    lookup = {}  # (stage, point key, replica) -> job id
    for point in grid_points(m):
        for i in order:
            st = stages[i]
            own = {v: point[v] for v in deps[st["name"]]}
            reps = list(range(replicas)) if replicated(st, tools) else [None]
            for r in reps:
                key = (st["name"], json.dumps(own, sort_keys=True), r)
                if key in lookup:
                    continue
                input_ids = []
                for inp in st.get("inputs", []):
                    inp_stage = stage_by_name[inp]
                    inp_point = json.dumps({v: point[v] for v in deps[inp]}, sort_keys=True)
                    if replicated(inp_stage, tools):
                        wanted = [r] if r is not None else list(range(replicas))
                        input_ids += [lookup[(inp, inp_point, k)] for k in wanted]
                    else:
                        input_ids.append(lookup[(inp, inp_point, None)])
                params = merge(m.get("defaults", {}).get(st["tool"], {}), st.get("params", {}))
                params = substitute(params, own, r, m["study"])
                jid = job_id(st["tool"], params, r, input_ids)
                lookup[key] = jid
                if jid in jobs:
                    continue
                directory = os.path.join(st["name"], *[f"{v}={format_value(own[v])}" for v in own])
                stem = st["name"] if r is None else f"{st['name']}-r{r}"
                filename = output_name(st, r)
                jobs[jid] = Job(jid, st["name"], st["tool"], params, own, r, input_ids, directory, stem, filename,
                                info=tools.describe(st["tool"]))
                by_stage.setdefault(st["name"], []).append(jid)
    for job in jobs.values():
        for inp in job.inputs:
            jobs[inp].downstream.append(job.id)
    return jobs, by_stage, deps
