"""Cost estimate of a campaign from the engines' own cost models: the "cost" of each tool's
description (--describe, describe.py). The runner knows no tool and no throughput of its own.

An engine states {"kind": "model", "work": UNIT, "amount": [FACTOR, ...], "rate": R,
"rates_when": [{"present": "key.path", "rate": R2}, ...], "measured": WHERE AND WHEN, "note": ...}:
a job's work is the product of the factors, its CPU time the work over the rate (that of the first
rates_when entry whose key path is in the job's parameters, else R). A factor is
  "particles"                      the particle count of the job's system: from the job upstream
                                   whose tool's output declares "adds_particles" ({"sum_over": LIST,
                                   "key": COUNT}: the sum of COUNT over the entries of LIST, plus
                                   the particles of its own first input, plus with "fill" a
                                   density × box volume, filled())
  "box_volume"                     the box volume of the job's system: the box.edges of the job
                                   itself or of the first job upstream that has them (an LB
                                   engine's lattice nodes at a node spacing of 1);
  {"param": "key.path", "default": X}   a number from the job's parameters;
  {"rule": NAME, ...}              a named count (RULES below) for run lengths no single key gives;
  a number                         a constant.
So a new engine whose run length is one key (steps of BD or DPD, lattice updates of LB from the
lattice size and steps) states its model without a change here. Tools whose jobs need no estimate
say {"kind": "negligible"} or {"kind": "not_estimated"}, with "why"; an engine must state a model.

The estimate is a plan, not a promise: compression phases count their max_cycles (an upper bound),
and the throughput depends on density and shape."""
import math

COST_KINDS = {"model", "negligible", "not_estimated"}


def mc_phases(params, rule):
    """Σ over the phases of their cycles; a compression counts its max_cycles (rule's
    default_max_cycles when not given): an upper bound."""
    total = 0
    for ph in params.get("phases", []):
        if isinstance(ph, dict):
            total += ph.get("cycles", ph.get("max_cycles", rule["default_max_cycles"] if ph.get("type") == "compress" else 0))
    return total


def dmc_cycles(params, rule):
    """Production cycles: `cycles`, or for a run given in Brownian time rule's cycles_per_time_step
    × time / the largest time step (a cycle advances at most δt/3: a lower bound); at least the
    schedule's segment cycles × repeat; plus the preliminary cycles of an equilibrium balance."""
    total = params.get("cycles", 0)
    if not total and "time" in params and params.get("time_step"):
        steps = [v for v in params["time_step"].values() if isinstance(v, (int, float)) and v > 0]
        total = int(rule["cycles_per_time_step"] * params["time"] / max(steps)) if steps else 0
    schedule = params.get("schedule", {})
    segments = schedule.get("segments", [])
    per_repeat = sum(s.get("cycles", 0) for s in segments if isinstance(s, dict))
    total = max(total, per_repeat * schedule.get("repeat", 1))
    balance = params.get("balance")
    if isinstance(balance, dict) and balance.get("mode", "equilibrium") == "equilibrium":
        total += balance.get("preliminary_cycles", rule["default_preliminary_cycles"])
    return total


def time_steps(params, rule):
    """Steps of a time-stepping engine (BD, DPD, LB): `steps`, or `time` / `time_step` rounded up."""
    if "steps" in params:
        return params["steps"]
    if "time" in params and params.get("time_step"):
        return math.ceil(params["time"] / params["time_step"])
    return 0


# name -> (function(params, rule), the keys the rule object must give)
RULES = {"mc_phases": (mc_phases, ("default_max_cycles",)),
         "dmc_cycles": (dmc_cycles, ("cycles_per_time_step", "default_preliminary_cycles")),
         "time_steps": (time_steps, ())}


def _number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def check_model(c, engine):
    """ValueError unless `c` is a cost statement the estimate can use; an engine needs a model."""
    if not isinstance(c, dict) or c.get("kind") not in COST_KINDS:
        raise ValueError(f"'cost' must be an object with kind {' | '.join(sorted(COST_KINDS))}")
    if c["kind"] != "model":
        if engine:
            raise ValueError(f"an engine must state a cost model (\"cost\": {{\"kind\": \"model\", \"work\", \"amount\", "
                             f"\"rate\", ...}}, docs/manifests.md); its description says kind \"{c['kind']}\"")
        return
    if not isinstance(c.get("work"), str) or not c["work"]:
        raise ValueError("a cost model names its unit of work ('work', e.g. \"trial moves\")")
    if not isinstance(c.get("amount"), list) or not c["amount"]:
        raise ValueError("a cost model's 'amount' is a non-empty list of factors")
    for f in c["amount"]:
        if f in ("particles", "box_volume") or _number(f):
            continue
        if isinstance(f, dict) and isinstance(f.get("param"), str) and _number(f.get("default", 0)):
            continue
        if isinstance(f, dict) and f.get("rule") in RULES and all(_number(f.get(k)) for k in RULES[f["rule"]][1]):
            continue
        raise ValueError(f"unknown cost factor {f!r}: \"particles\", \"box_volume\", a number, {{\"param\": \"key.path\", \"default\": x}} "
                         f"or {{\"rule\": one of {', '.join(sorted(RULES))}, with its keys}}")
    if not _number(c.get("rate")) or c["rate"] <= 0:
        raise ValueError("a cost model's 'rate' is a positive number of work units per second of one core")
    for w in c.get("rates_when", []):
        if not isinstance(w, dict) or not isinstance(w.get("present"), str) or not _number(w.get("rate")) or w["rate"] <= 0:
            raise ValueError("'rates_when' entries are {\"present\": \"key.path\", \"rate\": positive number}")


def _lookup(params, path):
    """(present, value) of a dotted key path in the parameters."""
    value = params
    for key in path.split("."):
        if not isinstance(value, dict) or key not in value:
            return False, None
        value = value[key]
    return True, value


def filled(params, fill):
    """Particles a builder places to a density over its box ({"when": key, "density": key.path,
    "default_density": x, "edges": key.path}: density × box volume when `when` is present)."""
    if not fill or fill["when"] not in params:
        return 0
    found, density = _lookup(params, fill["density"])
    found_edges, edges = _lookup(params, fill["edges"])
    if not found_edges or not isinstance(edges, list) or not all(_number(e) for e in edges):
        return 0
    return round((density if found and _number(density) else fill["default_density"]) * math.prod(edges))


def particles(job, jobs):
    """Particle count of a job's system, from the builder job(s) upstream (insertion adds)."""
    adds = job.info["output"].get("adds_particles")
    if adds:
        n = sum(int(c.get(adds["key"], 0)) for c in job.params.get(adds["sum_over"], []) if isinstance(c, dict))
        return n + filled(job.params, adds.get("fill")) + sum(particles(jobs[i], jobs) for i in job.inputs[:1])
    for i in job.inputs:
        n = particles(jobs[i], jobs)
        if n:
            return n
    return 0


def box_volume(job, jobs):
    """Box volume of a job's system: its own box.edges, else those of the first job upstream with them."""
    found, edges = _lookup(job.params, "box.edges")
    if found and isinstance(edges, list) and edges and all(_number(e) for e in edges):
        return math.prod(edges)
    for i in job.inputs:
        v = box_volume(jobs[i], jobs)
        if v:
            return v
    return 0


def factor(f, job, jobs):
    if f == "particles":
        return particles(job, jobs)
    if f == "box_volume":
        return box_volume(job, jobs)
    if _number(f):
        return f
    if "param" in f:
        present, value = _lookup(job.params, f["param"])
        return value if present and _number(value) else f.get("default", 0)
    return RULES[f["rule"]][0](job.params, f)


def model(job):
    """The job's tool's cost model, or None for a tool whose jobs are not estimated."""
    c = job.info["cost"]
    return c if c["kind"] == "model" else None


def rate(m, params):
    for w in m.get("rates_when", []):
        if _lookup(params, w["present"])[0]:
            return w["rate"]
    return m["rate"]


def job_cost(job, jobs):
    """(work, seconds of one core) of a job, from its tool's model; None for a tool without one."""
    m = model(job)
    if m is None:
        return None
    work = 1
    for f in m["amount"]:
        work *= factor(f, job, jobs)
    return work, work / rate(m, job.params)


def estimate(jobs):
    """{stage: (jobs, work, seconds)} for the stages of tools with a cost model."""
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
    work means the model could not size the job)."""
    out = {}
    for jid in ids:
        cost = job_cost(jobs[jid], jobs)
        if cost is not None and cost[1] > 0:
            out[jid] = cost[1]
    return out


def models(m, tools):
    """[(tool, cost model)] of the manifest's tools that have one, in stage order."""
    out, seen = [], set()
    for st in m["stages"]:
        c = tools.describe(st["tool"])["cost"]
        if c["kind"] == "model" and st["tool"] not in seen:
            seen.add(st["tool"])
            out.append((st["tool"], c))
    return out


def work_unit(used):
    """The unit of work of the models used ("trial moves"), or "work" for none or several."""
    units = {c["work"] for _, c in used}
    return units.pop() if len(units) == 1 else "work"


def rates_text(used):
    """"mc 9.57e+05/s, dmc 9.6e+05/s, dmc with field.dipoles 8.9e+04/s" for the models used."""
    parts = []
    for tool, c in used:
        parts.append(f"{tool} {c['rate']:.3g}/s")
        parts += [f"{tool} with {w['present']} {w['rate']:.3g}/s" for w in c.get("rates_when", [])]
    return ", ".join(parts)


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
