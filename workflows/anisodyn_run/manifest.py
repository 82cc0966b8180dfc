"""Manifest loading and validation. Every error names the manifest file and the JSON path.

Schema (docs/manifests.md):
  study        non-empty name, used as results/<study>/
  description  text
  defaults     {tool: {params}}: merged under the params of every stage of that tool
  grid         {var: [values...]}: Cartesian product of the lists (scalars; each list non-empty)
  zip          [[var, var, ...], ...]: groups of grid vars whose lists vary together (equal lengths)
  replicas     integer >= 1 (default 1)
  stages       [{name, tool, params, inputs, replicate, description}]
  report       {title, scalars: [...], plots: [...]} (report.py)
References in params: "${grid.x}" (a grid var), "${replica}" (the replica index, replicated stages
only), "${study}". A string that is exactly one reference takes the value's type; an object key
whose value is exactly a reference to a null grid value is left out.
What a tool is (replicated by default or not) comes from its description (describe.py).
"""
import json
import math
import re

REFERENCE = re.compile(r"\$\{([^}]*)\}")
TOP_KEYS = {"study", "description", "defaults", "grid", "zip", "replicas", "stages", "report"}
STAGE_KEYS = {"name", "tool", "params", "inputs", "replicate", "description", "output"}
NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")


class ManifestError(Exception):
    def __init__(self, path, expected, got=None):
        msg = f"at {path}: expected {expected}"
        if got is not None:
            text = json.dumps(got)
            msg += f", got {text if len(text) <= 60 else text[:57] + '...'}"
        super().__init__(msg)
        self.path = path


def load(path):
    """The manifest as parsed JSON; ManifestError for an unreadable file or invalid JSON."""
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        raise ManifestError("(file)", f"a readable manifest file ({e.strerror})")
    except json.JSONDecodeError as e:
        raise ManifestError(f"(line {e.lineno}, column {e.colno})", f"valid JSON ({e.msg})")


def merge(base, over):
    out = dict(base)
    for k, v in over.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def is_scalar(v):
    """A grid value: a number, string, boolean or null (null leaves out the key that refers to it)."""
    return v is None or isinstance(v, (str, int, float, bool))


def format_value(v):
    """The text of a grid value in paths and labels: 1 → "1", 0.15 → "0.15", "on" → "on"."""
    return v if isinstance(v, str) else json.dumps(v)


def validate(m, tools):
    """Checks the manifest against the schema; `tools` (describe.Tools) says whether anisodyn-<tool>
    exists and describes it (a tool that does not describe itself properly: DescriptionError).
    Returns the stages in a topological order of their inputs."""
    if not isinstance(m, dict):
        raise ManifestError("(top level)", "a JSON object", m)
    for k in m:
        if k not in TOP_KEYS and not k.startswith("_"):
            raise ManifestError(k, "one of " + ", ".join(sorted(TOP_KEYS)) + " (unknown key)")
    study = m.get("study")
    if not isinstance(study, str) or not NAME.match(study):
        raise ManifestError("study", "a study name of letters, digits, '_', '.', '-'", study)
    if not isinstance(m.get("description", ""), str):
        raise ManifestError("description", "a text", m.get("description"))
    validate_grid(m)
    replicas = m.get("replicas", 1)
    if isinstance(replicas, bool) or not isinstance(replicas, int) or replicas < 1:
        raise ManifestError("replicas", "an integer >= 1", replicas)
    defaults = m.get("defaults", {})
    if not isinstance(defaults, dict):
        raise ManifestError("defaults", "an object {tool: {params}}", defaults)
    for tool, block in defaults.items():
        if not isinstance(block, dict):
            raise ManifestError(f"defaults.{tool}", "an object of parameters for that tool", block)
    order = validate_stages(m, tools)
    validate_report(m)
    validate_everything_acts(m)
    return order


def validate_grid(m):
    grid = m.get("grid", {})
    if not isinstance(grid, dict):
        raise ManifestError("grid", "an object {variable: [values]}", grid)
    for var, values in grid.items():
        if not NAME.match(var):
            raise ManifestError(f"grid.{var}", "a variable name of letters, digits, '_', '.', '-'")
        if not isinstance(values, list) or not values:
            raise ManifestError(f"grid.{var}", "a non-empty list of values", values)
        for i, v in enumerate(values):
            if not is_scalar(v):
                raise ManifestError(f"grid.{var}[{i}]", "a number, string, boolean or null", v)
            if "/" in format_value(v) or format_value(v) in ("", ".", ".."):
                raise ManifestError(f"grid.{var}[{i}]", "a value usable in a directory name (no '/')", v)
    zipped = m.get("zip", [])
    if not isinstance(zipped, list):
        raise ManifestError("zip", "a list of groups of grid variables", zipped)
    seen = set()
    for g, group in enumerate(zipped):
        if not isinstance(group, list) or len(group) < 2:
            raise ManifestError(f"zip[{g}]", "a list of at least two grid variables", group)
        for j, var in enumerate(group):
            if var not in grid:
                raise ManifestError(f"zip[{g}][{j}]", "the name of a grid variable", var)
            if var in seen:
                raise ManifestError(f"zip[{g}][{j}]", "each grid variable in at most one zip group", var)
            seen.add(var)
            if len(grid[var]) != len(grid[group[0]]):
                raise ManifestError(f"zip[{g}][{j}]", f"a list as long as grid.{group[0]} ({len(grid[group[0]])} values)",
                                    len(grid[var]))
        tuples = [tuple(format_value(grid[v][i]) for v in group) for i in range(len(grid[group[0]]))]
        if len(set(tuples)) != len(tuples):
            raise ManifestError(f"zip[{g}]", "distinct combinations of the zipped values (a repeated one would run twice)")
    # a variable outside every zip group varies on its own: its values must differ
    for var, values in grid.items():
        if var not in seen and len({format_value(v) for v in values}) != len(values):
            raise ManifestError(f"grid.{var}", "distinct values (or put it in a zip group)", values)


def validate_stages(m, tools):
    stages = m.get("stages")
    if not isinstance(stages, list) or not stages:
        raise ManifestError("stages", "a non-empty list of stages", stages)
    index = {}
    for i, st in enumerate(stages):
        p = f"stages[{i}]"
        if not isinstance(st, dict):
            raise ManifestError(p, "an object {name, tool, params, inputs}", st)
        for k in st:
            if k not in STAGE_KEYS:
                raise ManifestError(f"{p}.{k}", "one of " + ", ".join(sorted(STAGE_KEYS)) + " (unknown key)")
        name = st.get("name")
        if not isinstance(name, str) or not NAME.match(name):
            raise ManifestError(f"{p}.name", "a stage name of letters, digits, '_', '.', '-'", name)
        if name in index:
            raise ManifestError(f"{p}.name", "a unique stage name", name)
        index[name] = i
        tool = st.get("tool")
        if not isinstance(tool, str) or not NAME.match(tool) or not tools.exists(tool):
            raise ManifestError(f"{p}.tool", "the name of an anisodyn tool (an executable anisodyn-<tool>)", tool)
        tools.describe(tool)
        if not isinstance(st.get("params", {}), dict):
            raise ManifestError(f"{p}.params", "an object", st.get("params"))
        if not isinstance(st.get("replicate", True), bool):
            raise ManifestError(f"{p}.replicate", "true or false", st.get("replicate"))
        out = st.get("output", "x.h5")
        if not isinstance(out, str) or not NAME.match(out) or "." not in out:
            raise ManifestError(f"{p}.output", "a plain file name with an extension for the stage's output (default <name>.h5)", out)
        inputs = st.get("inputs", [])
        if not isinstance(inputs, list):
            raise ManifestError(f"{p}.inputs", "a list of stage names", inputs)
    for i, st in enumerate(stages):
        for j, inp in enumerate(st.get("inputs", [])):
            if inp not in index:
                raise ManifestError(f"stages[{i}].inputs[{j}]", "the name of a stage of this manifest", inp)
            if inp == st["name"]:
                raise ManifestError(f"stages[{i}].inputs[{j}]", "another stage (a stage cannot read its own output)", inp)
    order = topological_order(stages, index)
    grid = m.get("grid", {})
    for i, st in enumerate(stages):
        params = merge(m.get("defaults", {}).get(st["tool"], {}), st.get("params", {}))
        check_references(params, f"stages[{i}].params", grid, replicated(st, tools))
    return order


def topological_order(stages, index):
    """Stage indices in an order where every stage follows its inputs; a cycle is a ManifestError."""
    state, order = {}, []

    def visit(i, trail):
        if state.get(i) == "done":
            return
        if state.get(i) == "active":
            names = [stages[k]["name"] for k in trail[trail.index(i):]] + [stages[i]["name"]]
            raise ManifestError(f"stages[{i}].inputs", "stage inputs without a cycle; found " + " -> ".join(names))
        state[i] = "active"
        for inp in stages[i].get("inputs", []):
            visit(index[inp], trail + [i])
        state[i] = "done"
        order.append(i)

    for i in range(len(stages)):
        visit(i, [])
    return order


def replicated(stage, tools):
    """Whether the stage runs once per replica: by default when its tool takes --replica (builders
    and engines, their descriptions say), while analysis stages aggregate the replicas."""
    if "replicate" in stage:
        return stage["replicate"]
    return tools.describe(stage["tool"])["replica"]


def check_references(value, path, grid, is_replicated):
    if isinstance(value, dict):
        for k, v in value.items():
            check_references(v, f"{path}.{k}", grid, is_replicated)
    elif isinstance(value, list):
        for k, v in enumerate(value):
            check_references(v, f"{path}[{k}]", grid, is_replicated)
    elif isinstance(value, str):
        for ref in REFERENCE.findall(value):
            if ref.startswith("grid."):
                if ref[5:] not in grid:
                    raise ManifestError(path, f"a reference to a grid variable (${{grid.<var>}} with <var> in: "
                                              f"{', '.join(grid) or 'none, the manifest has no grid'})", value)
            elif ref == "replica":
                if not is_replicated:
                    raise ManifestError(path, "${replica} only in a replicated stage", value)
            elif ref != "study":
                raise ManifestError(path, "a reference ${grid.<var>}, ${replica} or ${study}", value)


def referenced_vars(value):
    """Grid variables referenced anywhere in value."""
    if isinstance(value, dict):
        return set().union(*[referenced_vars(v) for v in value.values()]) if value else set()
    if isinstance(value, list):
        return set().union(*[referenced_vars(v) for v in value]) if value else set()
    if isinstance(value, str):
        return {r[5:] for r in REFERENCE.findall(value) if r.startswith("grid.")}
    return set()


def substitute(value, point, replica, study):
    """value with every reference replaced; a string that is exactly one reference takes its type.
    A key whose value is exactly a reference to a null grid value is left out, so that a zipped
    variable can drop a key at the grid points whose mode has no use for it (tools refuse such keys)."""
    if isinstance(value, dict):
        out = {k: substitute(v, point, replica, study) for k, v in value.items()}
        return {k: v for k, v in out.items() if not (v is None and isinstance(value[k], str) and REFERENCE.fullmatch(value[k]))}
    if isinstance(value, list):
        return [substitute(v, point, replica, study) for v in value]
    if not isinstance(value, str):
        return value

    def lookup(ref):
        if ref.startswith("grid."):
            return point[ref[5:]]
        return replica if ref == "replica" else study

    whole = REFERENCE.fullmatch(value)
    if whole:
        return lookup(whole.group(1))
    return REFERENCE.sub(lambda mo: format_value(lookup(mo.group(1))), value)


THEORY_KINDS = {"constant", "linear", "power", "exponential", "free_diffusion", "wertheim", "hasimoto", "periodic_rotation", "tirado_ratio", "fit_line",
                "spheroid", "pore_centreline"}
# The keys each report item reads (report.py): anything else would be silently ignored.
SCALAR_BLOCK_KEYS = {"stage", "names", "caption"}
PLOT_KEYS = {"name", "stage", "select", "log", "xlabel", "ylabel", "title", "caption", "theory"}
TABLE_PLOT_KEYS = PLOT_KEYS | {"table", "x", "y", "errors", "rows", "overlay"}
OVERLAY_KEYS = {"stage", "select", "label", "row"}
SCALAR_PLOT_KEYS = PLOT_KEYS | {"scalar", "x", "x_scale", "x_power", "y_scale", "series"}
BAR_PLOT_KEYS = PLOT_KEYS | {"scalar", "groups", "bars", "y_scale"}
SERIES_PLOT_KEYS = (PLOT_KEYS - {"stage"}) | {"x", "x_scale", "x_power", "y_scale", "series"}  # "series": a list of entries, each its own stage
SERIES_ENTRY_KEYS = {"stage", "scalar", "label", "select", "band", "x_scale", "y_scale", "at_x"}
THEORY_KEYS = {"constant": {"value"}, "linear": {"intercept", "slope"}, "power": {"prefactor", "exponent"},
               "exponential": {"tau", "amplitude"}, "free_diffusion": {"species", "component"}, "wertheim": {"scalar"},
               "hasimoto": {"boundary", "band"}, "periodic_rotation": {"band"}, "tirado_ratio": set(),
               "fit_line": set(), "spheroid": {"factor", "scale"}, "pore_centreline": {"formula", "radius", "pore_radius"}}
THEORY_NUMBERS = {"linear": {"intercept", "slope"}}  # keys a line needs, each a number
SPHEROID_FACTORS = ("A", "B", "t_ax", "t_perp", "r_ax", "r_perp", "t_ratio", "r_ratio")  # spheroid_theory.FACTORS


def check_keys(item, allowed, path, why):
    for k in item:
        if k not in allowed and not k.startswith("_"):
            raise ManifestError(f"{path}.{k}", f"no '{k}': it has no effect {why} (keys here: {', '.join(sorted(allowed))})")


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def check_select(select, path, grid):
    if not isinstance(select, dict):
        raise ManifestError(path, "an object {grid variable: value}", select)
    for var in select:
        if var not in grid:
            raise ManifestError(f"{path}.{var}", f"no '{var}': it has no effect, select picks values of grid variables ("
                                + (", ".join(grid) or "the manifest has none") + ")")


def check_series_entries(item, p, stages, grid):
    """The entries of a scalar plot's series list: each {stage, scalar, label, select, band}."""
    entries = item["series"]
    if not entries:
        raise ManifestError(f"{p}.series", "a non-empty list of {stage, scalar, label, select, band}", entries)
    for j, e in enumerate(entries):
        q = f"{p}.series[{j}]"
        if not isinstance(e, dict):
            raise ManifestError(q, "an object {stage, scalar, label, select, band}", e)
        check_keys(e, SERIES_ENTRY_KEYS, q, "in a series entry")
        if e.get("stage") not in stages:
            raise ManifestError(f"{q}.stage", "the name of a stage of this manifest", e.get("stage"))
        if not isinstance(e.get("scalar"), str):
            raise ManifestError(f"{q}.scalar", "the name of a scalar of the stage's output", e.get("scalar"))
        if not isinstance(e.get("label", ""), str):
            raise ManifestError(f"{q}.label", "a text", e.get("label"))
        check_select(e.get("select", {}), f"{q}.select", grid)
        if "band" in e and not (is_number(e["band"]) and 0 < e["band"] < 1):
            raise ManifestError(f"{q}.band", "a relative half-width between 0 and 1 (e.g. 0.02 for ±2%)", e["band"])
        for key in ("x_scale", "y_scale"):
            if key in e and (not is_number(e[key]) or e[key] == 0 or not math.isfinite(e[key])):
                raise ManifestError(f"{q}.{key}", "a non-zero number (overrides the plot's)", e[key])
        if "at_x" in e:
            if not is_number(e["at_x"]) or not math.isfinite(e["at_x"]):
                raise ManifestError(f"{q}.at_x", "a number: the x coordinate of the entry's one grid point", e["at_x"])
            if "x_scale" in e:
                raise ManifestError(f"{q}.x_scale", "no 'x_scale': it has no effect with at_x (the point is drawn at at_x)")


def check_panel(item, p, stages, grid):
    """A curve plot's `rows` (a panel: a row of subplots per value of that grid variable, a column per y) and
    `overlay` (a second stage's curves drawn over the plot's, in every row or in the one named by `row`)."""
    if "rows" in item and item["rows"] not in grid:
        raise ManifestError(f"{p}.rows", "a grid variable: a row of subplots per value (" + (", ".join(grid) or "the manifest has none") + ")",
                            item["rows"])
    if "overlay" not in item:
        return
    q = f"{p}.overlay"
    over = item["overlay"]
    if not isinstance(over, dict):
        raise ManifestError(q, "an object {stage, select, label, row}", over)
    check_keys(over, OVERLAY_KEYS, q, "in an overlay")
    if over.get("stage") not in stages:
        raise ManifestError(f"{q}.stage", "the name of a stage of this manifest (whose table the overlay draws)", over.get("stage"))
    if not isinstance(over.get("label", ""), str):
        raise ManifestError(f"{q}.label", "a text (the overlay's name in the legend)", over.get("label"))
    check_select(over.get("select", {}), f"{q}.select", grid)
    if "row" in over:
        if "rows" not in item:
            raise ManifestError(f"{q}.row", "no 'row': it has no effect, the plot is not a panel (no 'rows')")
        if format_value(over["row"]) not in [format_value(v) for v in grid[item["rows"]]]:
            raise ManifestError(f"{q}.row", f"a value of grid.{item['rows']} (the panel row to draw the overlay in)", over["row"])


def check_bars(item, p, grid):
    """A bar plot's `groups` (a group of bars along x per value) and `bars` (a bar per value in each group)."""
    for key in ("groups", "bars"):
        if item.get(key) not in grid:
            raise ManifestError(f"{p}.{key}", "a grid variable (" + (", ".join(grid) or "the manifest has none") + ")", item.get(key))
    if item["groups"] == item["bars"]:
        raise ManifestError(f"{p}.bars", "a grid variable other than groups", item["bars"])
    if "y_scale" in item and (not is_number(item["y_scale"]) or item["y_scale"] == 0 or not math.isfinite(item["y_scale"])):
        raise ManifestError(f"{p}.y_scale", "a non-zero number (the scalars and their errors are multiplied by it)", item["y_scale"])
    if "x" in item.get("log", ""):
        raise ManifestError(f"{p}.log", "'y' or '' on a bar plot (its x axis holds the groups)", item["log"])


def validate_raspberry(item, m):
    """report.raspberry (raspberry.py): an lb-diffusion stage, the grid variable of the box, and
    optionally the calibration: {"fit": grid variable} (spheres), "stokes", or {"file": path, "xi_bead": number}."""
    p = "report.raspberry"
    if not isinstance(item, dict):
        raise ManifestError(p, "an object {stage, box, calibration}", item)
    check_keys(item, {"stage", "box", "calibration", "plot"}, p, "in the raspberry block")
    tools = {st["name"]: st["tool"] for st in m["stages"]}
    if tools.get(item.get("stage")) != "lb-diffusion":
        raise ManifestError(f"{p}.stage", "the name of an lb-diffusion stage of this manifest", item.get("stage"))
    grid = m.get("grid", {})
    if item.get("box") not in grid:
        raise ManifestError(f"{p}.box", "the grid variable that sets the box edge (" + (", ".join(grid) or "the manifest has none") + ")",
                            item.get("box"))
    if "plot" in item:
        plot = item["plot"]
        if not isinstance(plot, dict):
            raise ManifestError(f"{p}.plot", "an object {x, series}", plot)
        check_keys(plot, {"x", "series"}, f"{p}.plot", "in the raspberry block's plot")
        for key in ("x", "series") if "series" in plot else ("x",):
            if plot.get(key) not in grid or plot.get(key) == item["box"]:
                raise ManifestError(f"{p}.plot.{key}", "a grid variable other than the box", plot.get(key))
    cal = item.get("calibration")
    q = f"{p}.calibration"
    if cal is None or cal == "stokes":  # no calibration: the frictions per body only
        return
    if not isinstance(cal, dict):
        raise ManifestError(q, '{"fit": grid variable} (fit the sphere lines), "stokes", or {"file": path, "xi_bead": number}', cal)
    if "fit" in cal:
        check_keys(cal, {"fit"}, q, "with fit")
        if cal["fit"] not in grid or cal["fit"] == item["box"]:
            raise ManifestError(f"{q}.fit", "a grid variable other than the box: one calibration line per value (xi_bead)", cal["fit"])
        return
    check_keys(cal, {"file", "xi_bead"}, q, "with file")
    if not isinstance(cal.get("file"), str) or not cal["file"]:
        raise ManifestError(f"{q}.file", "the path of a sphere study's raspberry_calibration.json (relative to the results folder)",
                            cal.get("file"))
    if not is_number(cal.get("xi_bead")):
        raise ManifestError(f"{q}.xi_bead", "a number: the bead friction whose calibration line to invert", cal.get("xi_bead"))


def validate_report(m):
    """The report block's structure (names of tables, columns and scalars are checked when the
    report is written, since they exist only in the outputs)."""
    rep = m.get("report", {})
    if not isinstance(rep, dict):
        raise ManifestError("report", "an object {title, scalars, plots}", rep)
    for k in rep:
        if k not in ("title", "scalars", "plots", "raspberry", "spheroid_reference"):
            raise ManifestError(f"report.{k}", "one of title, scalars, plots, raspberry, spheroid_reference (unknown key)")
    if "spheroid_reference" in rep:
        ref = rep["spheroid_reference"]
        if not isinstance(ref, dict):
            raise ManifestError("report.spheroid_reference", "an object {tolerance}", ref)
        check_keys(ref, {"tolerance"}, "report.spheroid_reference", "in the spheroid reference block")
        if "tolerance" in ref and not (is_number(ref["tolerance"]) and ref["tolerance"] > 0):
            raise ManifestError("report.spheroid_reference.tolerance", "a positive number (absolute)", ref["tolerance"])
    if "raspberry" in rep:
        validate_raspberry(rep["raspberry"], m)
    stages = {st["name"] for st in m["stages"]}
    grid = m.get("grid", {})
    for key in ("scalars", "plots"):
        items = rep.get(key, [])
        if not isinstance(items, list):
            raise ManifestError(f"report.{key}", "a list", items)
        for i, item in enumerate(items):
            p = f"report.{key}[{i}]"
            if not isinstance(item, dict):
                raise ManifestError(p, "an object", item)
            listed = key == "plots" and isinstance(item.get("series"), list)  # several scalars, each of its own stage
            if not listed and item.get("stage") not in stages:
                raise ManifestError(f"{p}.stage", "the name of a stage of this manifest", item.get("stage"))
            if key == "scalars":
                check_keys(item, SCALAR_BLOCK_KEYS, p, "in a scalars block")
                if not isinstance(item.get("names", ["*"]), list):
                    raise ManifestError(f"{p}.names", "a list of scalar names (wildcards allowed)", item.get("names"))
                continue
            if ("table" in item) + ("scalar" in item) + listed != 1:
                raise ManifestError(p, "one of 'table' (curves against a column), 'scalar' (a stage's scalar against a grid "
                                       "variable, or as grouped bars with 'bars') or 'series' as a list of {stage, scalar} "
                                       "(several scalars against a grid variable)")
            if "table" in item:
                check_keys(item, TABLE_PLOT_KEYS, p, "in a table plot")
                check_panel(item, p, stages, grid)
            elif "bars" in item:
                check_keys(item, BAR_PLOT_KEYS, p, "in a bar plot")
                check_bars(item, p, grid)
            elif listed:
                check_keys(item, SERIES_PLOT_KEYS, p, "in a scalar plot whose series is a list (each entry names its stage)")
                check_series_entries(item, p, stages, grid)
            else:
                check_keys(item, SCALAR_PLOT_KEYS, p, "in a scalar plot")
            check_select(item.get("select", {}), f"{p}.select", grid)
            if "table" in item and (not isinstance(item.get("y"), list) or not item["y"]):
                raise ManifestError(f"{p}.y", "a non-empty list of column names", item.get("y"))
            # A series list whose entries all give their own x (at_x) has no grid variable on x.
            fixed_x = listed and all(isinstance(e, dict) and "at_x" in e for e in item["series"])
            if fixed_x:
                for axis_key in ("x", "x_scale", "x_power"):
                    if axis_key in item:
                        raise ManifestError(f"{p}.{axis_key}", f"no '{axis_key}': it has no effect, every entry gives its own at_x")
            if "table" not in item and "bars" not in item and not fixed_x:
                for axis in ("x", "series") if "scalar" in item else ("x",):
                    value = item.get(axis)
                    if (axis == "x" or axis in item) and (not isinstance(value, str) or value not in grid):
                        raise ManifestError(f"{p}.{axis}", "a grid variable (" + (", ".join(grid) or "the manifest has none") + ")",
                                            value)
                if "y_scale" in item and (not is_number(item["y_scale"]) or item["y_scale"] == 0 or not math.isfinite(item["y_scale"])):
                    raise ManifestError(f"{p}.y_scale", "a non-zero number (the scalars and their errors are multiplied by it)", item["y_scale"])
                for axis_key, meaning in (("x_scale", "the grid value times it"), ("x_power", "(the grid value times x_scale) to this power")):
                    if axis_key not in item:
                        continue
                    value = item[axis_key]
                    if not is_number(value) or value == 0 or not math.isfinite(value):
                        raise ManifestError(f"{p}.{axis_key}", f"a non-zero number (the x coordinate is {meaning})", value)
                    if not all(is_number(v) for v in grid[item["x"]]):
                        raise ManifestError(f"{p}.{axis_key}", f"no '{axis_key}': it has no effect, the values of grid.{item['x']} are not "
                                                          "all numbers (they are drawn at their positions in the list)")
                    if axis_key == "x_power" and value < 0 and any(v == 0 for v in grid[item["x"]]):
                        raise ManifestError(f"{p}.x_power", f"a positive power: grid.{item['x']} holds 0", value)
            if not isinstance(item.get("log", ""), str) or set(item.get("log", "")) - set("xy"):
                raise ManifestError(f"{p}.log", "'x', 'y', 'xy' or ''", item.get("log"))
            for j, t in enumerate(item.get("theory", [])):
                if not isinstance(t, dict) or t.get("kind") not in THEORY_KINDS:
                    raise ManifestError(f"{p}.theory[{j}].kind", "one of " + ", ".join(sorted(THEORY_KINDS)),
                                        t.get("kind") if isinstance(t, dict) else t)
                if "columns" in t and "rows" not in item:
                    raise ManifestError(f"{p}.theory[{j}].columns", "no 'columns': it has no effect, the plot is not a panel (no 'rows')")
                check_keys(t, THEORY_KEYS[t["kind"]] | {"kind", "label", "columns"}, f"{p}.theory[{j}]", f"on a '{t['kind']}' line")
                if "columns" in t and (not isinstance(t["columns"], list) or not t["columns"] or any(c not in item["y"] for c in t["columns"])):
                    raise ManifestError(f"{p}.theory[{j}].columns", "a non-empty list of the plot's y columns (whose subplots draw the line)",
                                        t["columns"])
                if "bars" in item and t["kind"] != "constant":
                    raise ManifestError(f"{p}.theory[{j}].kind", "'constant' on a bar plot (its x axis holds groups, not values)", t["kind"])
                if t["kind"] == "fit_line" and "table" in item:
                    raise ManifestError(f"{p}.theory[{j}].kind", "a fitted line ('fit_line') only on a scalar plot (it fits the plotted scalars)",
                                        t["kind"])
                if t["kind"] == "spheroid" and t.get("factor") not in SPHEROID_FACTORS:
                    raise ManifestError(f"{p}.theory[{j}].factor", "one of " + ", ".join(SPHEROID_FACTORS) + " (spec 40 §8.6)", t.get("factor"))
                if t["kind"] == "spheroid" and "scale" in t and not is_number(t["scale"]):
                    raise ManifestError(f"{p}.theory[{j}].scale", "a number (the factor's multiplier)", t["scale"])
                if t["kind"] == "pore_centreline":
                    if "table" not in item:
                        raise ManifestError(f"{p}.theory[{j}].kind", "a centreline point ('pore_centreline') only on a curve plot of a pore table",
                                            t["kind"])
                    if t.get("formula", "haberman_sayre") not in ("haberman_sayre", "bohlin"):
                        raise ManifestError(f"{p}.theory[{j}].formula", "'haberman_sayre' or 'bohlin' (spec 70 §7.4)", t.get("formula"))
                    if not (is_number(t.get("radius")) and t["radius"] > 0):
                        raise ManifestError(f"{p}.theory[{j}].radius", "the sphere's radius (a positive number; lambda = radius / R_pore)",
                                            t.get("radius"))
                    if t.get("pore_radius", "R_pore") not in grid:
                        raise ManifestError(f"{p}.theory[{j}].pore_radius", "the grid variable of the pore radius", t.get("pore_radius", "R_pore"))
                if t["kind"] == "hasimoto" and t.get("boundary", "stick") not in ("stick", "slip"):
                    raise ManifestError(f"{p}.theory[{j}].boundary", "'stick' or 'slip'", t.get("boundary"))
                if "band" in t and not (is_number(t["band"]) and 0 < t["band"] < 1):
                    raise ManifestError(f"{p}.theory[{j}].band", "a relative half-width between 0 and 1 (e.g. 0.2 for ±20%)", t["band"])
                for number in sorted(THEORY_NUMBERS.get(t["kind"], ())):
                    if not is_number(t.get(number)):
                        raise ManifestError(f"{p}.theory[{j}].{number}", f"a number (the line's {number})", t.get(number))


def validate_everything_acts(m):
    """A grid variable no stage refers to, or defaults for a tool no stage runs, would change nothing."""
    stages = m["stages"]
    used_tools = {st["tool"] for st in stages}
    for tool in m.get("defaults", {}):
        if tool not in used_tools:
            raise ManifestError(f"defaults.{tool}", f"no defaults for '{tool}': it has no effect, no stage runs that tool "
                                                    f"(stages run: {', '.join(sorted(used_tools))})")
    referenced = set()
    for st in stages:
        referenced |= referenced_vars(merge(m.get("defaults", {}).get(st["tool"], {}), st.get("params", {})))
    for var in m.get("grid", {}):
        if var not in referenced:
            raise ManifestError(f"grid.{var}", f"no grid variable '{var}': it has no effect, no stage's params refer to it "
                                               f"(${{grid.{var}}})")
