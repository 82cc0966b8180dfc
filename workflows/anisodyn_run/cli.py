"""Command line of anisodyn-run (docs/manifests.md)."""
import argparse
import os
import socket
import sys
import time

from . import cost, executor, expand
from .describe import DescriptionError, Tools
from .jobdb import JobDb
from .manifest import ManifestError, load, replicated, validate

EXIT_BAD_INPUT, EXIT_FAILED, EXIT_INTERRUPTED = 2, 3, 130
DAG_LISTING_LIMIT = 60  # --dry-run lists every job (with its inputs) of campaigns up to this size


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="anisodyn-run", description="Runs a study manifest: expands the grid and replicas into a "
                                 "DAG of stage jobs, runs them with local workers, skips jobs that are up to date, resumes "
                                 "interrupted ones and writes results/<study>/report/.")
    ap.add_argument("manifest")
    ap.add_argument("--jobs", "-j", type=int, default=os.cpu_count() or 1, help="parallel jobs (default: the number of cores)")
    ap.add_argument("--dry-run", action="store_true", help="print the DAG, job counts and the estimated cost; run nothing")
    ap.add_argument("--only", metavar="STAGE", help="run only this stage's jobs (re-run even if up to date; inputs must exist)")
    ap.add_argument("--from", dest="from_stage", metavar="STAGE", help="re-run this stage and every stage after it")
    ap.add_argument("--status", action="store_true", help="summarise the campaign's jobs from its job database")
    ap.add_argument("--emit", nargs=2, metavar=("FORMAT", "DIR"), help="write a workflow for a cluster: 'snakemake DIR'")
    ap.add_argument("--no-report", action="store_true", help="do not write the report")
    ap.add_argument("--bin", default=os.environ.get("ANISODYN_BIN"), help="directory of the anisodyn executables")
    ap.add_argument("--results", default=os.environ.get("ANISODYN_RESULTS"), help="results directory (default: <repo>/results)")
    ap.add_argument("--campaign", help="campaign directory (default: <results>/<study>)")
    ap.add_argument("--quiet", action="store_true")
    return ap.parse_args(argv)


def repo_root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    root = repo_root()
    bin_dir = os.path.abspath(args.bin or os.path.join(root, "build", "bin"))
    results = os.path.abspath(args.results or os.path.join(root, "results"))
    tools = Tools(bin_dir)  # what each tool is, from its --describe (asked once per tool)
    try:
        if args.jobs < 1:
            raise ManifestError("--jobs", "at least 1", args.jobs)
        m = load(args.manifest)
        order = validate(m, tools)
        stage_names = [st["name"] for st in m["stages"]]
        for opt, value in (("--only", args.only), ("--from", args.from_stage)):
            if value is not None and value not in stage_names + ["report"]:
                raise ManifestError(opt, "a stage of the manifest (" + ", ".join(stage_names) + ") or 'report'", value)
        if args.emit and args.emit[0] != "snakemake":
            raise ManifestError("--emit", "the format 'snakemake'", args.emit[0])
    except ManifestError as e:
        where = args.manifest if not str(e).startswith("at --") else "command line"
        print(f"anisodyn-run: error: {where}: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except DescriptionError as e:  # the tools, not the manifest, are at fault
        print(f"anisodyn-run: error: {e}", file=sys.stderr)
        return EXIT_FAILED
    jobs, by_stage, deps = expand.expand(m, order, tools)
    campaign = os.path.abspath(args.campaign) if args.campaign else os.path.join(results, m["study"])
    if args.dry_run:
        return dry_run(m, jobs, by_stage, deps, campaign, tools)
    if args.status:
        return status(m, jobs, by_stage, campaign)
    if args.emit:
        from . import snakemake
        return snakemake.emit(m, jobs, by_stage, deps, bin_dir, root, os.path.abspath(args.emit[1]), args.manifest)
    return run(args, m, jobs, by_stage, campaign, bin_dir, root)


def selection(m, jobs, by_stage, args):
    """(selected ids, forced ids) for --only / --from; everything (nothing forced) otherwise."""
    if args.only in (None, "report") and args.from_stage in (None, "report"):
        return (set() if "report" in (args.only, args.from_stage) else set(jobs)), set()
    if args.only:
        ids = set(by_stage.get(args.only, []))
        return ids, ids
    start = set(by_stage.get(args.from_stage, []))
    forced, frontier = set(start), list(start)
    while frontier:
        for d in jobs[frontier.pop()].downstream:
            if d not in forced:
                forced.add(d)
                frontier.append(d)
    return set(jobs), forced


def run(args, m, jobs, by_stage, campaign, bin_dir, root):
    os.makedirs(campaign, exist_ok=True)
    db = JobDb(campaign)
    if runner_alive(db.data.get("runner")) and db.data["runner"]["pid"] != os.getpid():
        print(f"anisodyn-run: error: another anisodyn-run (pid {db.data['runner']['pid']}) is working on {campaign}; "
              "wait for it, or see --status", file=sys.stderr)
        return EXIT_FAILED
    db.data["study"] = m["study"]
    db.data["manifest"] = os.path.abspath(args.manifest)
    db.data["runner"] = {"pid": os.getpid(), "host": socket.gethostname(), "started": time.time()}
    selected, forced = selection(m, jobs, by_stage, args)
    t0 = time.time()
    if not args.quiet:
        print(f"[{m['study']}] {len(jobs)} jobs in {len(by_stage)} stages; {len(selected)} selected, {args.jobs} workers; "
              f"campaign {campaign}", file=sys.stderr)
    state, interrupted = executor.run(jobs, selected, forced, db, bin_dir, campaign, root, args.jobs, m["study"], args.quiet)
    db.data.pop("runner", None)
    counts = {}
    for jid in selected:
        s = state.get(jid, "pending")  # an interrupted run leaves jobs it never reached
        counts[s] = counts.get(s, 0) + 1
    ran, skipped = counts.get("done", 0), counts.get("skipped", 0)
    db.data.setdefault("runs", []).append({"started": t0, "seconds": round(time.time() - t0, 3), "ran": ran, "up_to_date": skipped,
                                            "failed": counts.get("failed", 0), "blocked": counts.get("blocked", 0),
                                            "interrupted": counts.get("interrupted", 0)})
    db.save()
    if interrupted:
        print(f"[{m['study']}] interrupted: {ran} jobs ran, {counts.get('interrupted', 0)} stopped at a checkpoint; "
              "run the same command again to resume", file=sys.stderr)
        return EXIT_INTERRUPTED
    failed = counts.get("failed", 0) + counts.get("blocked", 0)
    print(f"[{m['study']}] {ran} jobs ran, {skipped} up to date, {counts.get('failed', 0)} failed, {counts.get('blocked', 0)} blocked "
          f"in {time.time() - t0:.1f} s", file=sys.stderr)
    if failed:
        print(f"[{m['study']}] see `anisodyn-run --status {args.manifest}` for the failed jobs and their logs", file=sys.stderr)
        return EXIT_FAILED
    if args.no_report or args.only not in (None, "report") or not m.get("report"):
        return 0
    from . import report
    return report.generate(m, jobs, by_stage, campaign, quiet=args.quiet)


def dry_run(m, jobs, by_stage, deps, campaign, tools):
    points = len(expand.grid_points(m))
    print(f"study {m['study']}: {points} grid point{'s' if points != 1 else ''} x {m.get('replicas', 1)} replicas -> {len(jobs)} jobs")
    print(f"campaign directory: {campaign}")
    est = cost.estimate(jobs)
    used = cost.models(m, tools)
    unit = cost.work_unit(used)
    total_moves, total_seconds = 0, 0.0
    print(f"{'stage':<16} {'tool':<14} {'jobs':>6}  {'per':<28} {'inputs':<20} {unit:>12} {'CPU time':>9}")
    for st in m["stages"]:
        name = st["name"]
        per = ", ".join(deps[name]) or "-"
        if replicated(st, tools):
            per += " x replica"
        n, moves, seconds = est.get(name, (0, 0, 0.0))
        total_moves += moves
        total_seconds += seconds
        print(f"{name:<16} {st['tool']:<14} {len(by_stage.get(name, [])):>6}  {per:<28} {','.join(st.get('inputs', [])) or '-':<20} "
              f"{cost.human_count(moves) if moves else '-':>12} {cost.human_seconds(seconds) if moves else '-':>9}")
    present = sum(1 for j in jobs.values() if os.path.exists(os.path.join(campaign, j.output)))
    if used:
        print(f"total: {len(jobs)} jobs ({present} outputs already present); estimated {cost.human_count(total_moves)} {unit}, "
              f"{cost.human_seconds(total_seconds)} of one core (single-core throughputs from docs/performance.md: "
              f"{cost.rates_text(used)})")
    else:
        print(f"total: {len(jobs)} jobs ({present} outputs already present); no engine stage, nothing to estimate")
    listed = list(jobs.values()) if len(jobs) <= DAG_LISTING_LIMIT else list(jobs.values())[:1]
    print("jobs (inputs first):" if len(listed) > 1 else f"{len(jobs)} jobs; the first (all are listed up to {DAG_LISTING_LIMIT}):")
    for job in listed:
        ins = ", ".join(jobs[i].label for i in job.inputs)
        print(f"  {job.id}  {job.label:<40} <- {ins or '-'}")
    return 0


def runner_alive(runner):
    """Whether the runner recorded in the database is still running (on this host)."""
    if not runner or runner.get("host") != socket.gethostname():
        return False
    try:
        os.kill(runner["pid"], 0)
    except (ProcessLookupError, PermissionError):
        return False
    try:
        with open(f"/proc/{runner['pid']}/cmdline", "rb") as f:  # not a recycled pid
            return b"anisodyn-run" in f.read()
    except OSError:
        return False


def status(m, jobs, by_stage, campaign):
    db = JobDb(campaign)
    if not os.path.exists(db.path):
        print(f"study {m['study']}: no campaign yet ({campaign} has no job database)")
        return 0
    print(f"study {m['study']}: {len(jobs)} jobs; campaign {campaign}")
    active = runner_alive(db.data.get("runner"))
    if active:
        print(f"  a runner is working on it now (pid {db.data['runner']['pid']})")
    failed = []
    total_cpu = 0.0
    for st in m["stages"]:
        counts = {}
        for jid in by_stage.get(st["name"], []):
            rec = db.data["jobs"].get(jid, {})
            s = rec.get("state", "pending")
            if s == "running" and not active:
                s = "interrupted"  # its runner was stopped: the next run resumes it
            counts[s] = counts.get(s, 0) + 1
            total_cpu += rec.get("seconds", 0.0) if rec.get("state") == "done" else 0.0
            if s == "failed":
                failed.append((jobs[jid].label, rec.get("exit_code"), os.path.join(campaign, rec.get("err", jobs[jid].err))))
        text = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
        print(f"  {st['name']:<16} {len(by_stage.get(st['name'], [])):>5} jobs: {text}")
    for run in db.data.get("runs", [])[-3:]:
        print(f"  run at {time.strftime('%Y-%m-%d %H:%M:%S', time.localtime(run['started']))}: {run['ran']} ran, "
              f"{run['up_to_date']} up to date, {run['failed']} failed, {run['interrupted']} interrupted, {run['seconds']:.1f} s")
    print(f"  job time (done jobs, last run of each): {total_cpu:.1f} s")
    for label, rc, log in failed:
        print(f"  FAILED {label}: exit {rc}, log {log}")
    return 0
