#!/usr/bin/env python3
"""The study runner's ETA (workflows/anisodyn_run/executor.py, Progress) on a campaign expanded from
a manifest, without running anything: 2 packing fractions x (config -> mc -> 2 dmc replicas -> msd)
plus a hydro job, 150 particles, 300 MC and 40 000 DMC cycles.
  1. before any job has finished, the engine jobs count with the cost model's plan
     (particles x cycles / single-core throughput), the others are unknown;
  2. after the configurations finish in milliseconds the ETA still comes from the plan (it used to
     extrapolate their duration to every job and read 0:00);
  3. once a job of a stage has finished, that stage's mean replaces the plan, and the other stages
     of the same tool are scaled by how the finished jobs compared with their plan;
  4. running jobs count with what is left of them; the ETA is never below the longest job left;
  5. with nothing to go on (no plan, nothing finished) the ETA is unknown.
The plans come from the tools' own cost models (their --describe).
argv: [1] build bin dir, [2] scratch dir (unused), [3] source dir."""
import os
import sys

bin_dir, source = sys.argv[1], sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
from anisodyn_run import cost, expand  # noqa: E402
from anisodyn_run.describe import Tools  # noqa: E402
from anisodyn_run.executor import Progress  # noqa: E402
from anisodyn_run.manifest import validate  # noqa: E402

tools = Tools(bin_dir)

MANIFEST = {
    "study": "eta",
    "grid": {"eta": [0.1, 0.2]},
    "replicas": 2,
    "stages": [
        {"name": "config", "tool": "config", "replicate": False,
         "params": {"seed": 7, "species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}, "D_trans": [0.1, 0.1, 0.1]}],
                    "composition": [{"species": "hs", "count": 150}], "box": {"packing_fraction": "${grid.eta}"},
                    "placement": "lattice"}},
        {"name": "mc", "tool": "mc", "replicate": False, "inputs": ["config"],
         "params": {"seed": 8, "phases": [{"type": "nvt", "label": "melt", "cycles": 300}]}},
        {"name": "dmc", "tool": "dmc", "inputs": ["mc"],
         "params": {"seed": 9, "cycles": 40000, "time_step": {"hs": 0.01}, "frames": {"every_cycles": 400}}},
        {"name": "msd", "tool": "msd", "inputs": ["dmc"], "params": {"species": "hs"}},
        {"name": "hydro", "tool": "hydro", "output": "sphere.species.json",
         "params": {"species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}}]}},
    ],
}
failures = []


def check(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


def close(a, b):
    return a is not None and abs(a - b) <= 1e-9 * max(1.0, abs(b))


jobs, by_stage, _ = expand.expand(MANIFEST, validate(MANIFEST, tools), tools)
stage_jobs = {name: [jobs[j] for j in ids] for name, ids in by_stage.items()}
MC_PLAN = 150 * 300 / tools.describe("mc")["cost"]["rate"]       # particles x cycles / trial moves per second
DMC_PLAN = 150 * 40000 / tools.describe("dmc")["cost"]["rate"]
WORKERS = 2
planned = cost.planned_seconds(jobs, jobs)
check(sorted(planned.values()) == sorted([MC_PLAN] * 2 + [DMC_PLAN] * 4) and
      all(close(planned[j.id], DMC_PLAN) for j in stage_jobs["dmc"]),
      f"the plan covers the 2 mc jobs ({MC_PLAN:.3f} s) and the 4 dmc jobs ({DMC_PLAN:.2f} s), nothing else")

# 1. nothing finished: the engine jobs' plan, spread over the workers
progress = Progress("eta", len(jobs), WORKERS, True, planned)
all_jobs = list(jobs.values())
expect = (2 * MC_PLAN + 4 * DMC_PLAN) / WORKERS
check(close(progress.eta(all_jobs, []), expect), f"before any job finished: ETA {progress.eta(all_jobs, [])} = plan / workers {expect:.3f}")

# 2. the configurations finish in 10 ms: the engine jobs keep their plan; msd and hydro (no plan) take
#    the mean of the finished jobs without a plan
for job in stage_jobs["config"]:
    progress.record(job, 0.01)
left = [j for j in all_jobs if j.stage != "config"]
expect = (2 * MC_PLAN + 4 * DMC_PLAN + 3 * 0.01) / WORKERS
eta = progress.eta(left, [])
check(close(eta, expect) and eta > 1, f"after the configurations: ETA {eta:.3f} s (not 0:00) = {expect:.3f}")

# 3. the mc jobs take twice their plan: dmc is another tool and keeps its plan; then one dmc job takes
#    3x its plan and the stage's mean replaces the plan of the other dmc jobs
for job in stage_jobs["mc"]:
    progress.record(job, 2 * MC_PLAN)
left = stage_jobs["dmc"] + stage_jobs["msd"] + stage_jobs["hydro"]
expect = (4 * DMC_PLAN + 3 * 0.01) / WORKERS
check(close(progress.eta(left, []), expect), "a finished mc stage does not change the plan of the dmc jobs")
progress.record(stage_jobs["dmc"][0], 3 * DMC_PLAN)
left = stage_jobs["dmc"][1:] + stage_jobs["msd"] + stage_jobs["hydro"]
expect = (3 * 3 * DMC_PLAN + 3 * 0.01) / WORKERS
check(close(progress.eta(left, []), expect), f"after one dmc job took 3x its plan the others are expected to take as long ({expect:.2f} s)")

# 3b. a second stage of a measured tool is scaled by that tool's measured / planned ratio
second = dict(MANIFEST, stages=MANIFEST["stages"][:3] + [{"name": "dmc_long", "tool": "dmc", "inputs": ["mc"],
                                                          "params": {"seed": 10, "cycles": 80000, "time_step": {"hs": 0.01}}}])
jobs2, by_stage2, _ = expand.expand(second, validate(second, tools), tools)
progress2 = Progress("eta", len(jobs2), 1, True, cost.planned_seconds(jobs2, jobs2))
for jid in by_stage2["dmc"]:
    progress2.record(jobs2[jid], 1.5 * DMC_PLAN)
long_jobs = [jobs2[j] for j in by_stage2["dmc_long"]]
expect = len(long_jobs) * 1.5 * 2 * DMC_PLAN
check(close(progress2.eta(long_jobs, []), expect), f"an unmeasured dmc stage is scaled by the measured dmc jobs (1.5x): {expect:.2f} s")

# 4. running jobs count with what is left of them (3x plan expected): one has run 1x plan, one is past
#    its expected duration (about to end, 0 left); one job has not started
one_worker = Progress("eta", len(jobs), 1, True, planned)
one_worker.record(stage_jobs["dmc"][0], 3 * DMC_PLAN)
running = [(stage_jobs["dmc"][1], DMC_PLAN), (stage_jobs["dmc"][2], 10 * DMC_PLAN)]
eta = one_worker.eta([stage_jobs["dmc"][3]], running)
check(close(eta, (2 + 0 + 3) * DMC_PLAN), f"running jobs count with their remaining time: ETA {eta:.2f} s = 5x plan")
wide = Progress("eta", len(jobs), 16, True, planned)
check(close(wide.eta(all_jobs, []), DMC_PLAN), "with more workers than jobs the ETA is the longest job, not the sum / workers")

# 5. no plan and nothing finished: unknown ("?"), not 0:00
analysis_only = Progress("eta", 2, WORKERS, True, {})
check(analysis_only.eta(stage_jobs["msd"], []) is None, "analysis jobs with nothing finished: the ETA is unknown")
check(progress.eta([], []) == 0.0, "nothing left: ETA 0")

print(f"{len(failures)} failed")
assert not failures, f"{len(failures)} check(s) failed: {failures}"
