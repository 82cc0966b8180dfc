"""Local execution of a campaign's jobs with N workers.

A job is ready when its inputs are finished. It is skipped ("up-to-date") when its output exists
and the stamp beside it records the same job id and the same SHA-256 of every input file;
otherwise it runs `anisodyn-<tool> --config <job>.json --output <job>.h5 --input ... [--replica K]`
from the repository root (--replica for a replicated job of a tool whose description says it takes
one). An engine job interrupted earlier resumes from its checkpoint because the
command is the same. A failed job is reported with its log path; jobs that need its output are
blocked, the others go on.

All children are started and reaped by the main thread. Each child gets SIGTERM if the runner dies
(PR_SET_PDEATHSIG), even by SIGKILL, so the engines checkpoint instead of running on unattended.
"""
import ctypes
import json
import os
import signal
import subprocess
import sys
import time

from . import cost
from .jobdb import atomic_write_text

PR_SET_PDEATHSIG = 1


def _die_with_parent(parent_pid):
    def setup():
        try:
            ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
        except OSError:
            pass
        if os.getppid() != parent_pid:  # the runner died before prctl took effect
            os._exit(130)
    return setup


def command(job, jobs, bin_dir, campaign):
    cmd = [os.path.join(bin_dir, f"anisodyn-{job.tool}"), "--config", os.path.join(campaign, job.config),
           "--output", os.path.join(campaign, job.output)]
    for i in job.inputs:
        cmd += ["--input", os.path.join(campaign, jobs[i].output)]
    if job.replica is not None and job.info["replica"]:
        cmd += ["--replica", str(job.replica)]
    return cmd


def stamp_of(job, jobs, db, campaign):
    return {"job": job.id, "tool": job.tool,
            "inputs": {jobs[i].output: db.sha256(os.path.join(campaign, jobs[i].output)) for i in job.inputs}}


def up_to_date(job, jobs, db, campaign):
    out, stamp_path = os.path.join(campaign, job.output), os.path.join(campaign, job.directory, job.stem + ".stamp.json")
    if not (os.path.exists(out) and os.path.exists(stamp_path)):
        return False
    try:
        with open(stamp_path) as f:
            return json.load(f) == stamp_of(job, jobs, db, campaign)
    except (OSError, json.JSONDecodeError):
        return False


def write_config(job, campaign):
    os.makedirs(os.path.join(campaign, job.directory), exist_ok=True)
    path = os.path.join(campaign, job.config)
    text = json.dumps(job.params, indent=2, sort_keys=True) + "\n"
    if not os.path.exists(path) or open(path).read() != text:  # same bytes on a resume
        atomic_write_text(path, text)


class Progress:
    """Campaign progress on stderr: counts, elapsed time and an ETA.

    The ETA spreads the expected remaining seconds of every unfinished job over the workers (and is
    never less than the longest of them). A job is expected to take the mean duration of the
    finished jobs of its stage. Before any job of its stage has finished, an engine job takes its
    tool's cost model's plan (cost.py), scaled by how long the finished jobs of the same tool took against
    their plan; a job the model does not cover takes the mean of the finished uncovered jobs. The
    first jobs to finish are configurations (milliseconds): extrapolating from them alone made the
    ETA read 0:00 until the first engine job finished."""

    def __init__(self, study, total, workers, quiet, planned):
        self.study, self.total, self.workers, self.quiet = study, total, workers, quiet
        self.planned = planned            # job id -> seconds of one core, from the cost model
        self.t0, self.last = time.time(), 0.0
        self.durations = {}               # stage -> seconds of its finished jobs
        self.against_plan = {}            # tool -> [seconds taken, seconds planned] of its finished planned jobs
        self.unplanned = []               # seconds of finished jobs the model does not cover

    def record(self, job, seconds):
        self.durations.setdefault(job.stage, []).append(seconds)
        plan = self.planned.get(job.id)
        if plan is None:
            self.unplanned.append(seconds)
        else:
            sums = self.against_plan.setdefault(job.tool, [0.0, 0.0])
            sums[0] += seconds
            sums[1] += plan

    def expected(self, job):
        """Expected seconds of a job, or None when nothing is known about it yet."""
        ds = self.durations.get(job.stage)
        if ds:
            return sum(ds) / len(ds)
        plan = self.planned.get(job.id)
        if plan is not None:
            taken, planned = self.against_plan.get(job.tool, (0.0, 0.0))
            return plan * (taken / planned if planned > 0 else 1.0)
        return sum(self.unplanned) / len(self.unplanned) if self.unplanned else None

    def eta(self, remaining, running):
        """Seconds until the campaign ends, from the jobs not started and (job, elapsed) of the running
        ones; None when no job's duration can be estimated yet."""
        expected = [self.expected(job) for job in remaining] + [self.expected(job) for job, _ in running]
        if expected and all(e is None for e in expected):
            return None
        elapsed = [0.0] * len(remaining) + [t for _, t in running]
        left = [max((e or 0.0) - t, 0.0) for e, t in zip(expected, elapsed)]
        return max(sum(left) / self.workers, max(left, default=0.0))

    def show(self, counts, remaining, running, force=False):
        now = time.time()
        if self.quiet or (not force and now - self.last < 2.0):
            return
        self.last = now
        eta = self.eta(remaining, running)
        eta_text = "?" if eta is None else _clock(eta)
        print(f"[{self.study}] done {counts['done']}/{self.total} (up to date {counts['skipped']}), running {counts['running']}, "
              f"failed {counts['failed']}, left {counts['left']}; elapsed {_clock(now - self.t0)}, ETA {eta_text}",
              file=sys.stderr, flush=True)


def _clock(s):
    s = int(round(s))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


class LocalRun:
    """One invocation over a campaign: the selected jobs, their states, and the running children."""

    def __init__(self, jobs, selected, forced, db, bin_dir, campaign, repo_root, workers, study, quiet):
        self.jobs, self.selected, self.forced, self.db = jobs, selected, forced, db
        self.bin_dir, self.campaign, self.repo_root = bin_dir, campaign, repo_root
        self.workers, self.study, self.quiet = workers, study, quiet
        # jobs outside the selection are "external": their outputs must already exist if needed
        self.state = {jid: "external" for jid in jobs if jid not in selected}
        self.waiting = [jid for jid in jobs if jid in selected]
        self.running = {}  # jid -> (Popen, start time, log files)
        self.progress = Progress(study, len(self.waiting), workers, quiet, cost.planned_seconds(jobs, self.waiting))
        self.interrupted = False

    def stop(self, _signum=None, _frame=None):
        """SIGINT/SIGTERM: no new jobs; the running engines get SIGTERM and checkpoint."""
        self.interrupted = True
        for proc, _, _ in self.running.values():
            try:
                proc.send_signal(signal.SIGTERM)
            except ProcessLookupError:
                pass

    def counts(self):
        st = self.state
        return {"done": sum(1 for j in st if st[j] in ("done", "skipped")), "skipped": sum(1 for j in st if st[j] == "skipped"),
                "running": len(self.running), "failed": sum(1 for j in st if st[j] == "failed"), "left": len(self.waiting)}

    def inputs_state(self, job):
        """The set of {done, missing, failed, pending} over the job's inputs."""
        s = set()
        for i in job.inputs:
            st = self.state.get(i)
            if st == "external":
                s.add("done" if os.path.exists(os.path.join(self.campaign, self.jobs[i].output)) else "missing")
            elif st in ("done", "skipped"):
                s.add("done")
            elif st in ("failed", "blocked", "interrupted"):
                s.add("failed")
            else:
                s.add("pending")
        return s

    def start_ready_jobs(self):
        """Settles or launches every waiting job whose inputs are finished, up to the free workers."""
        launched = False
        for jid in list(self.waiting):
            if self.interrupted or len(self.running) >= self.workers:
                break
            job, ins = self.jobs[jid], self.inputs_state(self.jobs[jid])
            if "pending" in ins:
                continue
            self.waiting.remove(jid)
            if "failed" in ins or "missing" in ins:
                self.block(job, "an input job failed" if "failed" in ins else "an input is missing (run the stages before it)")
            elif jid not in self.forced and up_to_date(job, self.jobs, self.db, self.campaign):
                self.state[jid] = "skipped"
                self.db.update(jid, label=job.label, stage=job.stage, state="up-to-date", output=job.output)
            else:
                self.launch(job)
                launched = True
        return launched

    def block(self, job, why):
        self.state[job.id] = "blocked"
        self.db.update(job.id, label=job.label, stage=job.stage, state="blocked", reason=why)
        if not self.quiet:
            print(f"[{self.study}] blocked: {job.label}: {why}", file=sys.stderr)

    def launch(self, job):
        write_config(job, self.campaign)
        cmd = command(job, self.jobs, self.bin_dir, self.campaign)
        out = open(os.path.join(self.campaign, job.log), "w")
        err = open(os.path.join(self.campaign, job.err), "w")
        proc = subprocess.Popen(cmd, stdout=out, stderr=err, cwd=self.repo_root, preexec_fn=_die_with_parent(os.getpid()))
        self.running[job.id] = (proc, time.time(), (out, err))
        self.state[job.id] = "running"
        self.db.update(job.id, label=job.label, stage=job.stage, state="running", started=time.time(), command=cmd,
                       log=job.log, err=job.err, output=job.output)
        self.db.save()

    def reap_finished(self):
        finished = False
        for jid, (proc, t_start, files) in list(self.running.items()):
            rc = proc.poll()
            if rc is None:
                continue
            for f in files:
                f.close()
            del self.running[jid]
            self.settle(self.jobs[jid], rc, time.time() - t_start)
            finished = True
        return finished

    def settle(self, job, rc, seconds):
        """Records a finished child: done (with its stamp), interrupted, or failed."""
        if rc == 0:
            atomic_write_text(os.path.join(self.campaign, job.directory, job.stem + ".stamp.json"),
                              json.dumps(stamp_of(job, self.jobs, self.db, self.campaign), sort_keys=True))
            self.state[job.id] = "done"
            self.progress.record(job, seconds)
        elif rc in (130, -signal.SIGTERM, -signal.SIGINT) and self.interrupted:
            self.state[job.id] = "interrupted"
        else:
            self.state[job.id] = "failed"
            print(f"[{self.study}] FAILED: {job.label} (exit {rc}); log: {os.path.join(self.campaign, job.err)}", file=sys.stderr)
        self.db.update(job.id, state=self.state[job.id], exit_code=rc, seconds=round(seconds, 3), finished=time.time())
        self.db.save()

    def show_progress(self, force):
        now = time.time()
        running = [(self.jobs[j], now - t) for j, (_, t, _) in self.running.items()]
        self.progress.show(self.counts(), [self.jobs[j] for j in self.waiting], running, force=force)

    def run(self):
        old = {s: signal.signal(s, self.stop) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            while self.waiting or self.running:
                launched = self.start_ready_jobs()
                finished = self.reap_finished()
                if self.interrupted:
                    if not self.running:
                        break
                elif launched or finished:
                    self.show_progress(force=finished)
                    continue
                else:
                    self.show_progress(force=False)
                time.sleep(0.05)
        finally:
            for s, h in old.items():
                signal.signal(s, h)
            self.db.save()
        self.progress.show(self.counts(), [], [], force=True)
        return self.state, self.interrupted


def run(jobs, selected, forced, db, bin_dir, campaign, repo_root, workers, study, quiet=False):
    """Runs the selected job ids (inputs first); `forced` ids run even when up to date.
    Returns (the state of every job, whether the run was interrupted)."""
    return LocalRun(jobs, selected, forced, db, bin_dir, campaign, repo_root, workers, study, quiet).run()
