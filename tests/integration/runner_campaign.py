#!/usr/bin/env python3
"""anisodyn-run on a small campaign of hard spheres (2 packing fractions × 2 replicas:
config → mc → dmc → msd, a hydro job, a report):
  1. the DAG: job counts, and a stage that ignores a grid variable runs once for all its values;
  2. a full run, then a second run that runs nothing (every job up to date);
  3. a parameter change re-runs exactly the jobs downstream of it; --only / --from;
  4. a failing job is reported with its log, blocks only what needs it, and the run exits 3;
  5. a second runner on a campaign that is being run refuses; SIGKILL of the runner in the middle: the engines are stopped (they get
     SIGTERM and checkpoint), a second run finishes without re-running any completed job, and
     every output equals that of an uninterrupted campaign (values, apart from provenance); the same
     after SIGINT (exit 130), whose progress lines estimate the ETA from the cost model before any engine job finished;
  6. the emitted Snakefile, run with `snakemake --cores 2`, gives the same outputs (skipped
     with a note when snakemake is not installed)."""
import copy
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
from anisodyn_run.describe import Tools  # noqa: E402
from anisodyn_run.compare import differences  # noqa: E402

shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
runner = [sys.executable, os.path.join(source, "workflows", "anisodyn-run"), "--bin", bin_dir, "--quiet"]
D = 0.1061032953945969
MANIFEST = {
    "study": "spheres",
    "description": "runner test: hard spheres at two packing fractions, 2 replicas",
    "grid": {"eta": [0.1, 0.2]},
    "replicas": 2,
    "stages": [
        {"name": "config", "tool": "config", "replicate": False,
         "params": {"seed": 7, "species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}, "D_trans": [D, D, D]}],
                    "composition": [{"species": "hs", "count": 150}], "box": {"packing_fraction": "${grid.eta}"},
                    "placement": "lattice"}},
        {"name": "mc", "tool": "mc", "replicate": False, "inputs": ["config"],
         "params": {"seed": 8, "observe_every": 50, "phases": [{"type": "nvt", "label": "melt", "cycles": 300, "tune": True}]}},
        {"name": "dmc", "tool": "dmc", "inputs": ["mc"],
         "params": {"seed": 9, "cycles": 40000, "time_step": {"hs": 0.01}, "frames": {"every_cycles": 400}, "observe_every": 100}},
        {"name": "msd", "tool": "msd", "inputs": ["dmc"], "params": {"species": "hs"}},
        {"name": "hydro", "tool": "hydro", "output": "sphere.species.json",
         "params": {"species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}}], "shells": {"count": 3, "max_beads": 400}}},
    ],
    "report": {"scalars": [{"stage": "msd", "names": ["D_tot_hs"]}],
               "plots": [{"name": "msd", "stage": "msd", "table": "msd_hs", "x": "time", "y": ["msd_tot"], "log": "xy",
                          "theory": [{"kind": "free_diffusion", "species": "hs"}]},
                         {"name": "D", "stage": "msd", "scalar": "D_tot_hs", "x": "eta"}]},
}
failures = []


def check(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


def write(m, name="spheres.json"):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        json.dump(m, f, indent=1)
    return path


def run(manifest, results, *extra, timeout=600):
    return subprocess.run(runner + ["--results", results, "--jobs", "2", *extra, manifest], capture_output=True, text=True, timeout=timeout)


def last_run(results):
    return json.load(open(os.path.join(results, "spheres", ".anisodyn", "jobs.json")))["runs"][-1]


def outputs(campaign):
    return sorted(os.path.relpath(p, campaign) for p in glob.glob(os.path.join(campaign, "**", "*.h5"), recursive=True)
                  if "/report" not in p)


def same_outputs(a, b, what):
    fa, fb = outputs(a), outputs(b)
    diffs = [] if fa == fb else [f"file lists differ: {sorted(set(fa) ^ set(fb))}"]
    for f in fa:
        if f in fb:
            diffs += [f"{f}: {d}" for d in differences(os.path.join(a, f), os.path.join(b, f))]
    check(not diffs and fa, f"{what}: {len(fa)} outputs identical apart from provenance" + (f" -- {diffs[:5]}" if diffs else ""))


path = write(MANIFEST)
# 1. DAG
r = subprocess.run(runner + ["--dry-run", path], capture_output=True, text=True)
check(r.returncode == 0 and "2 grid points x 2 replicas -> 11 jobs" in r.stdout, "dry run: 2 x (config, mc, 2 dmc, msd) + 1 hydro = 11 jobs")
check(" hydro " in r.stdout and "trial moves" in r.stdout, "dry run lists every stage with its cost")

# 2. full run, then nothing to do
ref = os.path.join(tmp, "reference")
t0 = time.time()
r = run(path, ref)
check(r.returncode == 0, f"full campaign exit 0 ({time.time() - t0:.1f} s) {r.stderr[-500:]}")
check(last_run(ref)["ran"] == 11, f"11 jobs ran: {last_run(ref)}")
summary = os.path.join(ref, "spheres", "report", "summary.md")
check(os.path.exists(summary) and len(glob.glob(os.path.join(ref, "spheres", "report", "*.png"))) == 2, "report with 2 plots")
r = run(path, ref)
check(r.returncode == 0 and last_run(ref)["ran"] == 0 and last_run(ref)["up_to_date"] == 11, f"second run: nothing re-ran {last_run(ref)}")
r = subprocess.run(runner + ["--results", ref, "--status", path], capture_output=True, text=True)
check(r.returncode == 0 and "dmc" in r.stdout and "up-to-date 4" in r.stdout, "--status summarises the campaign")

# 3. a change of the DMC parameters re-runs the 4 DMC jobs and 2 MSD jobs only
work = os.path.join(tmp, "work")
shutil.copytree(ref, work)
changed = copy.deepcopy(MANIFEST)
changed["stages"][2]["params"]["observe_every"] = 200
cpath = write(changed, "changed.json")
r = run(cpath, work)
check(r.returncode == 0 and last_run(work)["ran"] == 6 and last_run(work)["up_to_date"] == 5, f"changed dmc params: 6 re-ran, 5 kept {last_run(work)}")
r = run(cpath, work, "--only", "msd")
check(r.returncode == 0 and last_run(work)["ran"] == 2, f"--only msd re-runs its 2 jobs {last_run(work)}")
r = run(cpath, work, "--from", "mc")
check(r.returncode == 0 and last_run(work)["ran"] == 8 and last_run(work)["up_to_date"] == 3, f"--from mc re-runs mc, dmc, msd (8) {last_run(work)}")

# 4. a failing job: a packing fraction the lattice cannot reach fails at config; the other point goes on
bad = copy.deepcopy(MANIFEST)
bad["grid"]["eta"] = [0.1, 0.9]
bpath = write(bad, "bad.json")
fail_dir = os.path.join(tmp, "failing")
r = run(bpath, fail_dir)
check(r.returncode == 3, f"a failed job makes the run exit 3 (got {r.returncode})")
check("FAILED" in r.stderr and "config/eta=0.9/config.err" in r.stderr, "the failure names the job and its log")
lr = last_run(fail_dir)
check(lr["failed"] == 1 and lr["blocked"] == 4 and lr["ran"] == 6, f"1 failed, its 4 dependants blocked, 6 others ran {lr}")

# 5. SIGKILL in the middle, then resume
killed = os.path.join(tmp, "killed")
proc = subprocess.Popen(runner + ["--results", killed, "--jobs", "1", path], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
campaign = os.path.join(killed, "spheres")
deadline = time.time() + 300
while time.time() < deadline:
    done_dmc = glob.glob(os.path.join(campaign, "dmc", "*", "dmc-r*.stamp.json"))
    partial = glob.glob(os.path.join(campaign, "dmc", "*", "*.partial"))
    if len(done_dmc) >= 1 and partial:
        break
    time.sleep(0.05)
second = subprocess.run(runner + ["--results", killed, "--jobs", "1", path], capture_output=True, text=True)
check(second.returncode == 3 and "another anisodyn-run" in second.stderr, "a second runner on a busy campaign refuses (exit 3)")
time.sleep(0.3)
proc.send_signal(signal.SIGKILL)
proc.wait()
stamps_before = {p: os.path.getmtime(p) for p in glob.glob(os.path.join(campaign, "**", "*.stamp.json"), recursive=True)}
# the running engine gets SIGTERM from the kernel when the runner dies, checkpoints and exits
deadline = time.time() + 60
while time.time() < deadline:
    ps = subprocess.run(["pgrep", "-f", "--", f"--output {campaign}"], capture_output=True, text=True).stdout.split()
    if not ps:
        break
    time.sleep(0.1)
check(not ps, "no engine of the killed campaign is left running")
checkpoints = glob.glob(os.path.join(campaign, "**", "*.checkpoint.h5"), recursive=True)
check(len(checkpoints) >= 1, f"the interrupted engine job left a checkpoint ({len(checkpoints)})")
r = run(path, killed)
lr = last_run(killed)
check(r.returncode == 0, "resumed campaign exit 0")
check(lr["up_to_date"] == len(stamps_before) and lr["ran"] == 11 - len(stamps_before),
      f"resume: {len(stamps_before)} jobs completed before the kill were kept, {lr['ran']} ran ({lr})")
check(all(os.path.getmtime(p) == t for p, t in stamps_before.items()), "no completed job was re-run (stamps untouched)")
same_outputs(os.path.join(ref, "spheres"), campaign, "killed and resumed vs uninterrupted")

# 5b. Ctrl-C (SIGINT): exit 130 after the running engines checkpoint; the next run resumes
interrupted = os.path.join(tmp, "interrupted")
with_progress = [a for a in runner if a != "--quiet"]
proc = subprocess.Popen(with_progress + ["--results", interrupted, "--jobs", "1", path], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
campaign = os.path.join(interrupted, "spheres")
deadline = time.time() + 300
while time.time() < deadline and not glob.glob(os.path.join(campaign, "dmc", "*", "*.partial")):
    time.sleep(0.05)
time.sleep(0.3)
proc.send_signal(signal.SIGINT)
_, err = proc.communicate(timeout=120)
check(proc.returncode == 130 and "run the same command again to resume" in err, f"SIGINT: exit 130 with a resume hint (got {proc.returncode})")
check(last_run(interrupted)["interrupted"] >= 1, f"the interrupted job is recorded {last_run(interrupted)}")
# the progress line after the first finished job (a configuration or hydro, in milliseconds) takes the ETA
# of the 4 dmc jobs still to run from the cost model (4 x 150 particles x 40 000 cycles at the rate of
# anisodyn-dmc's own cost model, its --describe, on 1 worker), not from the milliseconds
dmc_plan = 4 * 150 * 40000 / Tools(bin_dir).describe("dmc")["cost"]["rate"]
first_done = re.search(r"done 1/11 .*ETA (\d+):(\d\d)\n", err)
eta = int(first_done.group(1)) * 60 + int(first_done.group(2)) if first_done else None
check(eta is not None and eta >= int(dmc_plan),
      f"ETA after the first finished job, before any engine job finished: {eta} s (>= the 4 dmc jobs' plan, {dmc_plan:.0f} s)")
r = run(path, interrupted)
check(r.returncode == 0, "the run after SIGINT finishes")
same_outputs(os.path.join(ref, "spheres"), campaign, "interrupted by SIGINT and resumed vs uninterrupted")

# 6. Snakemake export
if shutil.which("snakemake"):
    smk = os.path.join(tmp, "snakemake")
    r = subprocess.run(runner + ["--emit", "snakemake", smk, path], capture_output=True, text=True)
    check(r.returncode == 0 and os.path.exists(os.path.join(smk, "Snakefile")) and
          os.path.exists(os.path.join(smk, "profiles", "slurm", "config.yaml")), "Snakefile and SLURM profile written")
    r = subprocess.run(["snakemake", "-s", os.path.join(smk, "Snakefile"), "-d", smk, "--cores", "2", "--quiet"],
                       capture_output=True, text=True, cwd=tmp, timeout=900)
    check(r.returncode == 0, f"snakemake --cores 2 exit 0 {r.stderr[-800:] if r.returncode else ''}")
    check(os.path.exists(os.path.join(smk, "report", "summary.md")), "snakemake wrote the report")
    same_outputs(os.path.join(ref, "spheres"), smk, "snakemake vs anisodyn-run")
else:
    print("note: snakemake is not installed (scripts/setup --with-optional installs it): the export run is skipped")

print(f"{len(failures)} failed")
assert not failures, f"{len(failures)} check(s) failed: {failures}"
