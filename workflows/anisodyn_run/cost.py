"""Cost estimate of a campaign in trial moves (N particles × cycles per engine job), converted to
CPU time with the single-core throughputs measured by the engine benchmarks (docs/performance.md).
The estimate is a plan, not a promise: compression phases count their max_cycles (an upper bound),
and the throughput depends on density and shape."""
import math

# Single-thread trial moves per second, bench/mc_throughput.cpp (2026-11-22) and
# bench/dmc_throughput.cpp (2026-11-24, with skin lists; medians of three rounds, docs/performance.md).
THROUGHPUT = {
    "mc": 9.57e5,          # 2000 boards 12×3.46×1, η = 0.20
    "dmc": 9.6e5,          # 2000 boards 12×1×1 + 200 spheres, η = 0.34 nematic (the slowest hard-core case)
    "dmc_dipolar": 8.9e4,  # 1500 dipolar cubes with Ewald, field on
}


def particles(job, jobs):
    """Particle count of a job's system, from the config job(s) upstream (insertion adds)."""
    if job.tool == "config":
        n = sum(int(c.get("count", 0)) for c in job.params.get("composition", []) if isinstance(c, dict))
        return n + sum(particles(jobs[i], jobs) for i in job.inputs[:1])
    for i in job.inputs:
        n = particles(jobs[i], jobs)
        if n:
            return n
    return 0


def cycles(job):
    p = job.params
    if job.tool == "mc":
        total = 0
        for ph in p.get("phases", []):
            if isinstance(ph, dict):
                total += ph.get("cycles", ph.get("max_cycles", 10**6 if ph.get("type") == "compress" else 0))
        return total
    if job.tool == "dmc":
        total = p.get("cycles", 0)
        if not total and "time" in p and p.get("time_step"):
            # a run given in Brownian time: t per cycle is A δt/3 (spec 70 §1.1); A = 1 is a lower bound
            steps = [v for v in p["time_step"].values() if isinstance(v, (int, float)) and v > 0]
            total = int(3 * p["time"] / max(steps)) if steps else 0
        segments = p.get("schedule", {}).get("segments", [])
        per_repeat = sum(s.get("cycles", 0) for s in segments if isinstance(s, dict))
        total = max(total, per_repeat * p.get("schedule", {}).get("repeat", 1))
        balance = p.get("balance")
        if isinstance(balance, dict) and balance.get("mode", "equilibrium") == "equilibrium":
            total += balance.get("preliminary_cycles", 10**4)
        return total
    return 0


def job_cost(job, jobs):
    """(trial moves, seconds of one core) of an engine job; None for a tool the model does not cover."""
    if job.tool not in ("mc", "dmc"):
        return None
    moves = particles(job, jobs) * cycles(job)
    rate = THROUGHPUT["dmc_dipolar" if job.tool == "dmc" and "dipoles" in job.params.get("field", {}) else job.tool]
    return moves, moves / rate


def estimate(jobs):
    """{stage: (jobs, trial moves, seconds)} for the engine stages."""
    out = {}
    for job in jobs.values():
        cost = job_cost(job, jobs)
        if cost is None:
            continue
        n, m, s = out.get(job.stage, (0, 0, 0.0))
        out[job.stage] = (n + 1, m + cost[0], s + cost[1])
    return out


def planned_seconds(jobs, ids):
    """{job id: seconds of one core} from the model, for the given jobs it covers (a plan of zero
    trial moves means the model could not size the job)."""
    out = {}
    for jid in ids:
        cost = job_cost(jobs[jid], jobs)
        if cost is not None and cost[1] > 0:
            out[jid] = cost[1]
    return out


def human_seconds(s):
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    if s < 172800:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.1f} d"


def human_count(x):
    if x == 0:
        return "0"
    e = int(math.floor(math.log10(x)))
    return f"{x / 10**e:.2f}e{e}"
