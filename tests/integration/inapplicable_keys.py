#!/usr/bin/env python3
"""Keys that have no effect in the chosen mode are refused, tool by tool.

Walks every documented key whose effect depends on a mode (or on the input) and sets it where it
does not apply (anisodyn-config, -mc, -dmc, -hydro, the analysis stages and anisodyn-run), on a configuration that otherwise runs: each case must exit with code 2, name the
configuration file and the key's JSON path, say that the key has no effect, and write nothing.
Each walked key must appear in its tool's documentation page (so the table follows the docs), and
every base configuration must run as it is (so a refusal is due to the key alone).
"""
import copy
import json
import os
import re
import shutil
import subprocess
import sys

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
runner = [sys.executable, os.path.join(source, "workflows", "anisodyn-run"), "--bin", bin_dir]
DOCS = {tool: open(os.path.join(source, "docs", page)).read() for tool, page in
        {"config": "config.md", "mc": "mc.md", "dmc": "dmc.md", "run": "manifests.md", "hydro": "hydro.md",
         **{stage: "analysis.md" for stage in ("msd", "vanhove", "structure", "order", "response", "microrheology")}}.items()}


def write_json(name, value):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        json.dump(value, f)
    return path


def tool(name, *args):
    return subprocess.run([os.path.join(bin_dir, "anisodyn-" + name), "-q", *args], capture_output=True, text=True)


BOARD = {"name": "board", "shape": {"type": "cuboid", "edges": [1, 2, 6]}, "D_trans": [0.03, 0.03, 0.04], "D_rot": [0.01, 0.01, 0.05]}
BALL = {"name": "ball", "shape": {"type": "sphere", "diameter": 1}, "D_trans": [0.1, 0.1, 0.1]}
PROBE = {"name": "probe", "shape": {"type": "sphere", "diameter": 1}, "D_trans": [0.1, 0.1, 0.1]}

CONFIG = {"seed": 1, "species": [BOARD, BALL],
          "composition": [{"species": "board", "count": 8, "orientation": {"mode": "aligned", "axis": "L"}},
                          {"species": "ball", "count": 8}],
          "box": {"packing_fraction": 0.02}, "placement": "lattice"}
MC = {"seed": 2, "observe_every": 10,
      "phases": [{"type": "compress", "method": "npt", "packing_fraction": 0.03, "max_cycles": 200000},
                 {"type": "npt", "pressure": 0.01, "cycles": 20},
                 {"type": "nvt", "cycles": 20, "tune": True}]}
DMC = {"seed": 3, "cycles": 20, "time_step": {"probe": 0.01},
       "balance": {"mode": "equilibrium", "reference": "probe", "preliminary_cycles": 20},
       "moves": {"rotation": "exponential"},
       "field": {"direction": [1, 0, 0], "orientational": {"strength": 1.0, "axis": "W"}},
       "tracer": {"species": "probe", "pe": 1.0}}
DMC_BALLS = {"cycles": 20, "time_step": {"ball": 0.01}}

# Input states for mc and dmc: boards, balls and one probe; and balls alone.
mixed = write_json("mixed.json", dict(CONFIG, species=[BOARD, BALL, PROBE],
                                      composition=CONFIG["composition"] + [{"species": "probe", "count": 1}]))
balls = write_json("balls.json", {"seed": 1, "species": [BALL], "composition": [{"species": "ball", "count": 8}],
                                  "box": {"edges": [8, 8, 8]}})
for cfg, out in ((mixed, "mixed.h5"), (balls, "balls.h5")):
    r = tool("config", "--config", cfg, "--output", os.path.join(tmp, out))
    assert r.returncode == 0, r.stderr
MIXED, BALLS = os.path.join(tmp, "mixed.h5"), os.path.join(tmp, "balls.h5")

# (label, tool, base configuration, input, {key path: value} to set, the path the error must name)
CASES = [
    # anisodyn-config
    ("orientation of a sphere", "config", CONFIG, None, {"composition[1].orientation": {"mode": "random"}}, "composition[1].orientation"),
    ("axis with random orientations", "config", CONFIG, None, {"composition[0].orientation": {"mode": "random", "axis": "T"}},
     "composition[0].orientation.axis"),
    ("director with random orientations", "config", CONFIG, None, {"composition[0].orientation": {"mode": "random", "director": [1, 0, 0]}},
     "composition[0].orientation.director"),
    ("random_azimuth with random orientations", "config", CONFIG, None,
     {"composition[0].orientation": {"mode": "random", "random_azimuth": True}}, "composition[0].orientation.random_azimuth"),
    ("max_attempts_per_particle on a lattice", "config", CONFIG, None, {"max_attempts_per_particle": 50}, "max_attempts_per_particle"),
    ("box aspect with explicit edges", "config", CONFIG, None, {"box": {"edges": [40, 40, 40], "aspect": [1, 1, 3]}}, "box.aspect"),
    # anisodyn-mc
    ("quick_step with NPT compression", "mc", MC, MIXED, {"phases[0].quick_step": 0.01}, "phases[0].quick_step"),
    ("pressure_start with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].pressure_start": 0.1},
     "phases[0].pressure_start"),
    ("pressure_growth with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].pressure_growth": 2},
     "phases[0].pressure_growth"),
    ("cycles_per_step with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].cycles_per_step": 10},
     "phases[0].cycles_per_step"),
    ("plateau_tolerance with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].plateau_tolerance": 0.1},
     "phases[0].plateau_tolerance"),
    ("squeeze_window with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].squeeze_window": 0.1},
     "phases[0].squeeze_window"),
    ("box_moves with quick compression", "mc", MC, MIXED, {"phases[0].method": "quick", "phases[0].box_moves": "per_axis"},
     "phases[0].box_moves"),
    ("cycles in a compression", "mc", MC, MIXED, {"phases[0].cycles": 10}, "phases[0].cycles"),
    ("pressure in an nvt phase", "mc", MC, MIXED, {"phases[2].pressure": 1.0}, "phases[2].pressure"),
    ("box_moves in an nvt phase", "mc", MC, MIXED, {"phases[2].box_moves": "isotropic"}, "phases[2].box_moves"),
    ("packing_fraction in an npt phase", "mc", MC, MIXED, {"phases[1].packing_fraction": 0.1}, "phases[1].packing_fraction"),
    ("method in an nvt phase", "mc", MC, MIXED, {"phases[2].method": "quick"}, "phases[2].method"),
    ("max_cycles in an npt phase", "mc", MC, MIXED, {"phases[1].max_cycles": 10}, "phases[1].max_cycles"),
    ("squeeze_sweeps in an nvt phase", "mc", MC, MIXED, {"phases[2].squeeze_sweeps": 3}, "phases[2].squeeze_sweeps"),
    ("target_acceptance when nothing tunes", "mc", MC, MIXED,
     {"phases": [{"type": "nvt", "cycles": 10}], "target_acceptance": 0.3}, "target_acceptance"),
    ("tune_every when nothing tunes", "mc", MC, MIXED, {"phases": [{"type": "nvt", "cycles": 10}], "tune_every": 5}, "tune_every"),
    ("frames in time in a preparation run", "mc", MC, MIXED, {"frames": {"every_time": 10}}, "frames.every_time"),
    ("frames after a switch in a preparation run", "mc", MC, MIXED, {"frames": {"after_switch": {"every_cycles": 1, "for_cycles": 5}}},
     "frames.after_switch"),
    # anisodyn-dmc
    ("smoothing_cycles at equilibrium", "dmc", DMC, MIXED, {"balance.smoothing_cycles": 5}, "balance.smoothing_cycles"),
    ("preliminary_cycles per cycle", "dmc", DMC, MIXED, {"balance": {"mode": "per_cycle", "reference": "probe", "preliminary_cycles": 10}},
     "balance.preliminary_cycles"),
    ("max_iterations per cycle", "dmc", DMC, MIXED, {"balance": {"mode": "per_cycle", "reference": "probe", "max_iterations": 2}},
     "balance.max_iterations"),
    ("tolerance without a preliminary run", "dmc", DMC, MIXED, {"balance.preliminary_cycles": 0, "balance.tolerance": 0.01},
     "balance.tolerance"),
    ("preliminary keys with nothing to balance", "dmc", DMC_BALLS, BALLS, {"balance.preliminary_cycles": 30}, "balance.preliminary_cycles"),
    ("sequential_order with the exponential map", "dmc", DMC, MIXED, {"moves.sequential_order": "LWT"}, "moves.sequential_order"),
    ("rotation moves of spheres", "dmc", DMC_BALLS, BALLS, {"moves.rotation": "sequential"},
     "moves.rotation"),
    ("D_rot of a sphere", "dmc", DMC, MIXED, {"species.ball.D_rot": [0.1, 0.1, 0.1]}, "species.ball.D_rot"),
    ("check_direction without an orientational field", "dmc", DMC, MIXED,
     {"field": {"direction": [1, 0, 0], "check_direction": False, "dipoles": {"gamma": 1, "species": ["ball"]}}}, "field.check_direction"),
    ("Ewald accuracy with the minimum-image sum", "dmc", DMC, MIXED,
     {"field.dipoles": {"gamma": 1, "species": ["ball"], "minimum_image_only": True, "accuracy": 1e-4}}, "field.dipoles.accuracy"),
    ("initially with schedule segments", "dmc", dict(DMC, cycles=None), MIXED,
     {"field.initially": "on", "schedule": {"segments": [{"field": "off", "cycles": 10}]}}, "field.initially"),
    ("repeat without segments", "dmc", DMC, MIXED, {"schedule": {"repeat": 2}}, "schedule.repeat"),
]

# A pulled-tracer DMC trajectory of boards, balls and the probe, with frames, for the analysis stages.
TRAJ = os.path.join(tmp, "traj.h5")
r = tool("dmc", "--config", write_json("traj.json", dict(DMC, cycles=200, frames={"every_cycles": 10})), "--input", MIXED, "--output", TRAJ)
assert r.returncode == 0, r.stderr
MSD = {"species": "board"}
VANHOVE = {"species": "ball", "times": [0.001]}
STRUCTURE = {"pairs": [["board", "board"]], "r_max": 4.0}
ORDER = {"species": "board"}
RESPONSE = {"species": "board", "switch_on": 0.0005, "switch_off": 0.001}
ACTIVE = {"mode": "active", "species": "probe", "steady_from": 0.0}
SPHERE = {"name": "s", "shape": {"type": "sphere", "diameter": 1}}
HYDRO = {"species": [dict(SPHERE, bead_radii=[0.2, 0.15, 0.1])], "symmetry": True}
CASES += [
    # analysis stages
    ("msd direction without a field reference", "msd", MSD, TRAJ, {"direction": [0, 0, 1]}, "direction"),
    ("msd axis with the box axes", "msd", MSD, TRAJ, {"axis": "L"}, "axis"),
    ("msd director_species with the box axes", "msd", MSD, TRAJ, {"director_species": "board"}, "director_species"),
    ("van Hove direction without par/perp", "vanhove", VANHOVE, TRAJ, {"direction": [1, 0, 0]}, "direction"),
    ("angular bin width without angular axes", "vanhove", VANHOVE, TRAJ, {"angular_bin_width": 0.05}, "angular_bin_width"),
    ("angular dimension without angular axes", "vanhove", VANHOVE, TRAJ, {"angular_dimension": 3}, "angular_dimension"),
    ("structure direction with the director", "structure", STRUCTURE, TRAJ, {"reference": "director", "direction": [1, 0, 0]}, "direction"),
    ("structure axis with the field", "structure", STRUCTURE, TRAJ, {"axis": "L"}, "axis"),
    ("structure director_species with the field", "structure", STRUCTURE, TRAJ, {"director_species": "board"}, "director_species"),
    ("cylinder radius without a reference", "structure", STRUCTURE, TRAJ, {"reference": "none", "cylinder_radius": 1.0}, "cylinder_radius"),
    ("slab half height without a reference", "structure", STRUCTURE, TRAJ, {"reference": "none", "slab_half_height": 1.0}, "slab_half_height"),
    ("rod axis without S_rod", "order", ORDER, TRAJ, {"observables": ["U"], "rod_axis": "T"}, "rod_axis"),
    ("field direction without S_cube", "order", ORDER, TRAJ, {"observables": ["U", "B2"], "field_direction": [1, 0, 0]}, "field_direction"),
    ("chain threshold without S_cube", "order", ORDER, TRAJ, {"observables": ["U"], "chain_threshold": {"gamma": 13}}, "chain_threshold"),
    ("response main axis with a U signal", "response", RESPONSE, TRAJ, {"signal": "U_L", "main_axis": "L"}, "main_axis"),
    ("response field direction with B2", "response", RESPONSE, TRAJ, {"field_direction": [1, 0, 0]}, "field_direction"),
    ("kT without a force", "microrheology", ACTIVE, TRAJ, {"pe": 1.0, "kT": 2.0}, "kT"),
    ("radius with beta_force", "microrheology", ACTIVE, TRAJ, {"beta_force": 2.0, "radius": 0.5}, "radius"),
    ("tracer_diameter with force", "microrheology", ACTIVE, TRAJ, {"force": 2.0, "tracer_diameter": 1.0}, "tracer_diameter"),
    ("bin width without a density map", "microrheology", ACTIVE, TRAJ, {"density_map": False, "bin_width": 0.5}, "bin_width"),
    ("on-axis radius without a density map", "microrheology", ACTIVE, TRAJ, {"density_map": False, "on_axis_radius": 1.0},
     "on_axis_radius"),
    ("wake threshold without a density map", "microrheology", ACTIVE, TRAJ, {"density_map": False, "wake_threshold": 0.8},
     "wake_threshold"),
    ("order axis without a density map", "microrheology", ACTIVE, TRAJ, {"density_map": False, "order_axis": "T"}, "order_axis"),
    ("bath species without a density map", "microrheology", ACTIVE, TRAJ, {"density_map": False, "bath_species": "ball"}, "bath_species"),
    ("bin width with dz_bin and rho_bin", "microrheology", ACTIVE, TRAJ, {"dz_bin": 0.5, "rho_bin": 0.5, "bin_width": 0.25}, "bin_width"),
    ("steady_distance at Pe = 0", "microrheology", ACTIVE, TRAJ, {"steady_from": None, "pe": 0.0, "steady_distance": 1.0},
     "steady_distance"),
    # anisodyn-hydro
    ("shells with bead radii", "hydro", HYDRO, None, {"species[0].shells": {"count": 3}}, "species[0].shells"),
    ("default shells no species uses", "hydro", HYDRO, None, {"shells": {"count": 3}}, "shells"),
    ("default construction no species uses", "hydro", HYDRO, None,
     {"construction": "cell_centres", "species[0].construction": "surface_grid"}, "construction"),
    ("default extrapolation no species uses", "hydro", HYDRO, None,
     {"extrapolation": "quadratic", "species[0].extrapolation": "linear"}, "extrapolation"),
    ("default bead radii no species uses", "hydro", HYDRO, None,
     {"bead_radii": [0.2, 0.15, 0.1], "species": [dict(SPHERE, shells={"count": 3, "max_beads": 200})]}, "bead_radii"),
]
BASES = (("msd", MSD, TRAJ), ("vanhove", VANHOVE, TRAJ), ("structure", STRUCTURE, TRAJ), ("order", ORDER, TRAJ),
         ("response", RESPONSE, TRAJ), ("microrheology", ACTIVE, TRAJ), ("hydro", HYDRO, None))

RUN_GOOD = {"study": "keys", "grid": {"eta": [0.02, 0.03]}, "replicas": 1,
            "stages": [{"name": "config", "tool": "config", "params": dict(CONFIG, box={"packing_fraction": "${grid.eta}"})},
                       {"name": "msd", "tool": "msd", "inputs": ["config"], "params": {}}],
            "report": {"scalars": [{"stage": "msd", "names": ["D_*"]}],
                       "plots": [{"name": "p", "stage": "msd", "table": "msd_board", "y": ["msd_tot"]},
                                 {"name": "q", "stage": "msd", "scalar": "D_tot_board", "x": "eta"}]}}
SERIES_PLOT_WITH_STAGE = {"name": "q", "stage": "msd", "x": "eta", "series": [{"stage": "msd", "scalar": "D_tot_board"}]}
RUN_CASES = [  # (label, mutation of the manifest, the path the error must name[, the documented key when not its last part])
    ("a grid variable no stage uses", lambda m: m["grid"].update(W=[1, 8]), "grid.W"),
    ("defaults for a tool no stage runs", lambda m: m.update(defaults={"dmc": {"seed": 4}}), "defaults.dmc"),
    ("series in a table plot", lambda m: m["report"]["plots"][0].update(series="eta"), "report.plots[0].series"),
    ("errors in a scalar plot", lambda m: m["report"]["plots"][1].update(errors=False), "report.plots[1].errors"),
    ("select on a variable that is not in the grid", lambda m: m["report"]["plots"][0].update(select={"phi": 0.1}),
     "report.plots[0].select.phi", "select"),
    ("tau on a constant line", lambda m: m["report"]["plots"][1].update(theory=[{"kind": "constant", "value": 1, "tau": 2}]),
     "report.plots[1].theory[0].tau"),
    ("caption-like key in a scalars block", lambda m: m["report"]["scalars"][0].update(xlabel="x"), "report.scalars[0].xlabel"),
    ("x_scale in a table plot", lambda m: m["report"]["plots"][0].update(x_scale=2), "report.plots[0].x_scale"),
    ("a stage beside a series list", lambda m: m["report"]["plots"].__setitem__(1, SERIES_PLOT_WITH_STAGE), "report.plots[1].stage"),
]


def documented(tool_name, path):
    key = re.split(r"[.\[]", path.replace("]", ""))[-1]
    if key.isdigit():
        key = path.split(".")[-1]
    return f"`{key}`" in DOCS[tool_name] or f'"{key}"' in DOCS[tool_name] or re.search(rf"\b{re.escape(key)}\b", DOCS[tool_name])


def set_path(config, path, value):
    """config with `path` (dotted, [i] for list items) set to value; None deletes the key."""
    node, parts = config, re.findall(r"[^.\[\]]+", path)
    for part in parts[:-1]:
        node = node[int(part)] if isinstance(node, list) else node.setdefault(part, {})
    last = parts[-1]
    if value is None and isinstance(node, dict):
        node.pop(last, None)
    elif isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


failures, passed = 0, 0


def check(label, result, config_path, json_path, output):
    global failures, passed
    problems = []
    if result.returncode != 2:
        problems.append(f"exit {result.returncode}, expected 2")
    message = result.stderr
    if config_path not in message:
        problems.append(f"the message does not name {config_path}")
    if json_path not in message:
        problems.append(f"the message does not name {json_path}")
    if "no effect" not in message:
        problems.append("the message does not say the key has no effect")
    if any(os.path.exists(output + suffix) for suffix in ("", ".partial", ".checkpoint.h5")):
        problems.append("output left behind")
    if problems:
        failures += 1
        print(f"FAIL {label}: {'; '.join(problems)}\n     {message.strip()[:400]}")
    else:
        passed += 1
        print(f"ok   {label}: {message.strip().splitlines()[-1][:200]}")


# The base configurations run as they are.
for name, base, input_path in (("config", CONFIG, None), ("mc", MC, MIXED), ("dmc", DMC, MIXED),
                               ("dmc", DMC_BALLS, BALLS)) + BASES:
    path = write_json(f"base-{name}.json", base)
    args = ["--config", path, "--output", os.path.join(tmp, f"base-{name}-{len(base)}.h5")] + (["--input", input_path] if input_path else [])
    r = tool(name, *args)
    assert r.returncode == 0, f"base configuration of {name} fails: {r.stderr}"

for k, (label, tool_name, base, input_path, changes, json_path) in enumerate(CASES):
    config = copy.deepcopy(base)
    for key in [k for k, v in config.items() if v is None]:
        del config[key]
    for path, value in changes.items():
        set_path(config, path, value)
    if not documented(tool_name, json_path):
        failures += 1
        print(f"FAIL {label}: '{json_path}' is not in docs/ for anisodyn-{tool_name}")
        continue
    config_path = write_json(f"case{k}.json", config)
    output = os.path.join(tmp, f"case{k}.h5")
    args = ["--config", config_path, "--output", output] + (["--input", input_path] if input_path else [])
    check(label, tool(tool_name, *args), config_path, json_path, output)

r = subprocess.run(runner + ["--dry-run", write_json("run-good.json", RUN_GOOD)], capture_output=True, text=True)
assert r.returncode == 0, f"base manifest fails: {r.stderr}"
for k, (label, mutate, json_path, *doc_key) in enumerate(RUN_CASES):
    m = copy.deepcopy(RUN_GOOD)
    mutate(m)
    if not documented("run", doc_key[0] if doc_key else json_path):
        failures += 1
        print(f"FAIL {label}: '{json_path}' is not in docs/manifests.md")
        continue
    path = write_json(f"run{k}.json", m)
    results = os.path.join(tmp, f"results{k}")
    r = subprocess.run(runner + ["--results", results, path], capture_output=True, text=True)
    check(label, r, path, json_path, os.path.join(results, "keys"))

print(f"{passed} passed, {failures} failed")
assert failures == 0, f"{failures} case(s) failed"
