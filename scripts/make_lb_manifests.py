#!/usr/bin/env python3
"""Writes the LB study manifests of spec 60 part D (Ustach & Faller) and their smokes from spec 40's
parameters, so that box sizes, flow speeds and run lengths follow from the formulas, not by hand.
Run from anywhere: scripts/make_lb_manifests.py"""
import json
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "manifests")
U_WALL = 0.013976   # spec 40 §7.2: 2.20 m/s in sigma/t0
NU_SIM = 0.8        # spec 40 §1.1
DT = 0.01           # MD time step (t0); the LB step is 2 DT
ROW = 200           # MD steps per recording (spec 40 §1: 2 t0)
L_ELLIPSOID = [27, 32, 38, 48, 55, 64, 76, 94]      # spec 40 §7.1
RADII = [2.25, 2.75, 3.25, 3.75, 4.25, 4.75, 5.25, 5.75]
RECORDINGS, RUNS = 200_000, 4                       # per box, in 4 runs (spec 40 §7.1 Decision)


def write(name, manifest):
    """manifests/<name>.json (name may hold a folder: validation/...)."""
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(manifest, f, indent=2, ensure_ascii=False)
        f.write("\n")


def sphere_config(seed):
    return {"name": "config", "tool": "config", "replicate": False, "params": {
        "seed": seed, "placement": "lattice",
        "species": [{"name": "raspberry", "shape": {"type": "sphere", "diameter": "${grid.d}"}}],
        "composition": [{"species": "raspberry", "count": 1}],
        "box": {"edges": ["${grid.L}"] * 3}}}


def diffusion_stages(shape, seed, xi, steps, fit, window_from, box="L", names=("config", "lb", "diffusion")):
    """Config, free thermal run and lb-diffusion of one raspberry in a periodic box of edge ${grid.<box>}."""
    config, lb, diffusion = names
    return [
        {"name": config, "tool": "config", "replicate": False, "params": {
            "seed": seed, "placement": "lattice", "species": [{"name": "raspberry", "shape": shape}],
            "composition": [{"species": "raspberry", "count": 1}], "box": {"edges": [f"${{grid.{box}}}"] * 3}}},
        {"name": lb, "tool": "lb", "inputs": [config], "params": {
            "seed": seed + 1, "time_step": DT, "steps": steps, "observe_every": 10 * ROW, "frames": {"every_steps": ROW},
            "raspberries": {"xi_bead": xi}}},
        {"name": diffusion, "tool": "lb-diffusion", "inputs": [lb], "params": {
            **({"fit": fit} if fit else {}), **({"window": {"from": window_from}} if window_from else {})}},
    ]


# --- D2a: Stokes-flow drag of a fixed raspberry sphere (spec 40 §7.2) -------------------------------
def resistance_manifest(smoke):
    if smoke:
        grid = {"d": [6.5], "xi_bead": [50, 1000], "L": [32]}
        t_run, t_window, blocks = 60, 20, 5
    else:
        grid = {"d": [6.5, 11.5], "xi_bead": [10, 25, 50, 100, 200, 400, 600, 800, 1000], "L": [40, 50, 64]}
        t_run, t_window, blocks = 4000, 200, 10
    steps = round(t_run / DT)
    m = {
        "study": "lb_bead_resistance_sweep" + ("-smoke" if smoke else ""),
        "description": ("D2a smoke: " if smoke else "Study D2a (spec 60 D2, spec 40 §7.2; Ustach & Faller): ")
        + "a raspberry sphere (outer layer R, inner R - 0.5, simple-cubic fill, centre bead; spec 40 §5) held fixed at the centre of a "
          "cubic box, the deterministic D3Q19 fluid (rho = 6.004, nu = 0.8, xi_bead scaled by s = 0.8/5.6757 as nominal water values, "
          "spec 40 §1.1) between walls (one solid node layer at y = 0, bounding the periodic box on both sides) moving along z at "
          f"U = {U_WALL} sigma/t0 (2.20 m/s); the fluid starts as the plug flow U everywhere; the drag over U is xi^t_col, reported as "
          "xi^t/(6 pi eta R) (anisodyn-lb-drag). "
        + (f"R = 3.25, box 32, {t_run} t0 ({steps // 2} LB steps, about two of the slowest mode's decay times L^2/(4 pi^2 nu)): not steady; "
           f"the last {t_window} t0 averaged." if smoke else
           f"Decision: the grid of spec 60 D2 (R = 3.25 and 5.75; xi_bead 10 ... 1000) at boxes 50 and the checks 40 and 64; {t_run} t0 "
           f"(ten relaxation times of the drag at the largest box, measured as 398 t0 at L = 64, docs/validation.md), the last "
           f"{t_window} t0 (100 recordings) averaged. The diffusion part D2b is not in this manifest yet."),
        "replicas": 1,
        "grid": grid,
        "stages": [
            sphere_config(71),
            {"name": "lb", "tool": "lb", "inputs": ["config"], "params": {
                "seed": 72, "time_step": DT, "steps": steps, "observe_every": ROW,
                "fluid": {"thermal": False, "initial_velocity": [0, 0, U_WALL], "warmup_steps": 0},
                "raspberries": {"xi_bead": "${grid.xi_bead}", "fixed": True},
                "walls": {"normal": "y", "velocity": [0, 0, U_WALL]}}},
            {"name": "drag", "tool": "lb-drag", "inputs": ["lb"], "params": {
                "window": {"from": t_run - t_window}, "blocks": blocks}},
        ],
        "report": {
            "title": "D2a" + (" smoke" if smoke else "") + ": Stokes drag of a fixed raspberry sphere",
            "scalars": [{"stage": "drag", "names": ["xi_t_over_6pi_eta_R", "R_eff_t", "xi_t_water", "xi_t_SI"],
                         "caption": "translational friction of the fixed raspberry (water units: divided by s; ratio and radius in the run's units)"}],
            "plots": [{"name": "xi_t_ratio", "stage": "drag", "scalar": "xi_t_over_6pi_eta_R", "x": "xi_bead", "series": "d",
                       "select": {"L": 32 if smoke else 50},
                       "theory": [{"kind": "constant", "value": 1, "label": "Stokes, 6 pi eta R"}],
                       "xlabel": "xi_bead (nominal, M0/t0)", "ylabel": "xi^t_col / (6 pi eta R)",
                       "title": "Translational friction against bead friction (d = 2R)"}]
            + ([] if smoke else [{"name": "xi_t_box", "stage": "drag", "scalar": "xi_t_over_6pi_eta_R", "x": "L", "x_power": -1, "series": "d",
                                  "select": {"xi_bead": 1000}, "xlabel": "1/L (1/sigma)", "ylabel": "xi^t_col / (6 pi eta R)",
                                  "title": "Finite-size check at xi_bead = 1000"}]),
        },
    }
    return m


def add_diffusion_half(m):
    """D2b (spec 60 D2, spec 40 §7.1): the same spheres free in the thermal fluid, in D3's eight boxes scaled with R,
    2e5 recordings per box in 4 runs; xi^t from the Hasimoto extrapolation and xi^r from D_r (report block raspberry)."""
    radii = [d / 2 for d in m["grid"]["d"]]
    pairs = [(2 * r, round(l * r / 4.25)) for r in radii for l in L_ELLIPSOID]
    m["grid"]["d"] = [p[0] for p in pairs]
    m["grid"]["L_free"] = [p[1] for p in pairs]
    m["zip"] = [["d", "L_free"]]
    m["stages"] += diffusion_stages({"type": "sphere", "diameter": "${grid.d}"}, 75, "${grid.xi_bead}", RECORDINGS // RUNS * ROW, None, None,
                                    box="L_free", names=("config_free", "lb_free", "diffusion"))
    m["replicas"] = RUNS
    m["stages"][1]["replicate"] = False  # D2a's deterministic runs need one replica
    m["description"] = m["description"].replace(
        "The diffusion part D2b is not in this manifest yet.",
        f"D2b: the same spheres free in the thermal fluid, in D3's boxes L = round(L_ell R/4.25) (spec 40 §7.1), {RECORDINGS} recordings "
        f"per box in {RUNS} runs; xi^t = kT/D_0 from the Hasimoto line and xi^r = kT/D_r (mean over the boxes) in the report's raspberry "
        "section, against xi_bead with the Stokes and SED lines at 1.")
    m["report"]["raspberry"] = {"stage": "diffusion", "box": "L_free", "plot": {"x": "xi_bead", "series": "d"}}



def stokes_box_validation():
    """The D2a drag of one raspberry at five box sizes, each run until steady (the drag relaxes
    exponentially, in 135 t0 at L = 40 and 398 t0 at L = 64): the mobility U/F against 1/L and its
    fitted intercept (docs/validation.md)."""
    m = resistance_manifest(False)
    boxes, t_runs, t_window = [24, 32, 40, 50, 64], [1300, 1300, 1300, 4000, 4000], 200
    m["study"] = "lb_stokes_drag_box"
    m["description"] = ("Validation of D2a (docs/validation.md): the fixed raspberry sphere R = 3.25 at xi_bead = 1000 (nominal) in the "
                        "deterministic fluid between walls moving at U (as lb_bead_resistance_sweep), boxes 24 ... 64, run for "
                        f"{t_runs} t0 (about ten relaxation times of the drag: 135 t0 at L = 40, 398 t0 at L = 64), the last {t_window} t0 averaged; "
                        "the mobility U/F against 1/L with its fitted line (intercept 1/xi_0).")
    m["grid"] = {"d": [6.5], "xi_bead": [1000], "L": boxes, "steps": [round(t / DT) for t in t_runs], "from": [t - t_window for t in t_runs]}
    m["zip"] = [["L", "steps", "from"]]
    m["stages"][1]["params"]["steps"] = "${grid.steps}"
    m["stages"][2]["params"]["window"] = {"from": "${grid.from}"}
    m["report"] = {"title": "D2a validation: drag against box size",
                   "scalars": [{"stage": "drag", "names": ["xi_t_over_6pi_eta_R", "R_eff_t", "mobility_t"], "caption": "per box"}],
                   "plots": [{"name": "mobility", "stage": "drag", "scalar": "mobility_t", "x": "L", "x_power": -1,
                              "theory": [{"kind": "fit_line", "label": "1/xi_0 + c_1 / L"}],
                              "xlabel": "1/L (1/sigma)", "ylabel": "U / F (t0/M0)", "title": "Mobility of the fixed raspberry against 1/L"}]}
    write("validation/lb_stokes_drag_box", m)


stokes_box_validation()


def einstein_validation():
    """Fluctuation and dissipation of the whole engine: a free raspberry's D_t in a periodic box
    against kT over the same raspberry's friction held fixed in the flow a body force drives through
    that box (Hasimoto's periodic array, whose mobility is the periodic system's, Dünweg & Kremer)."""
    edge, steps_free, runs = 16, 2_000_000, 4
    m = {
        "study": "lb_einstein_periodic",
        "description": "Validation (docs/validation.md): the raspberry sphere R = 2.25, xi_bead = 50 (nominal) in a periodic 16^3 box of the "
                       "spec 40 fluid. (1) Held fixed in the deterministic fluid driven by a body force 1e-4 along z for 900 t0 (ten decay times "
                       "of the mean flow, rho V / xi): xi = F / U with U the fluid's mean velocity, the last 200 t0. (2) Free in the thermal fluid, "
                       f"{runs} runs of {steps_free // 100} t0: D_t from the MSD over lags 40 ... 120 t0 (after five decay times L^2/(4 pi^2 nu) "
                       "= 8 t0 of the slowest fluid mode). Einstein: D_t = kT mobility_t.",
        "replicas": runs,
        "grid": {"d": [4.5], "L": [edge]},
        "stages": [
            {"name": "config", "tool": "config", "replicate": False, "params": {
                "seed": 111, "placement": "centre", "species": [{"name": "raspberry", "shape": {"type": "sphere", "diameter": "${grid.d}"}}],
                "composition": [{"species": "raspberry", "count": 1}], "box": {"edges": ["${grid.L}"] * 3}}},
            {"name": "fixed", "tool": "lb", "inputs": ["config"], "replicate": False, "params": {
                "seed": 112, "time_step": DT, "steps": 90_000, "observe_every": 1000,
                "fluid": {"thermal": False, "warmup_steps": 0, "body_force": [0, 0, 1e-4]},
                "raspberries": {"xi_bead": 50, "fixed": True}}},
            {"name": "drag", "tool": "lb-drag", "inputs": ["fixed"], "params": {"window": {"from": 700}, "blocks": 5}},
            {"name": "free", "tool": "lb", "inputs": ["config"], "params": {
                "seed": 113, "time_step": DT, "steps": steps_free, "observe_every": 10_000, "frames": {"every_steps": ROW},
                "raspberries": {"xi_bead": 50}}},
            {"name": "diffusion", "tool": "lb-diffusion", "inputs": ["free"], "params": {"fit": {"t_min": 40, "t_max": 120}}},
        ],
        "report": {"title": "Einstein relation of the LB engine",
                   "scalars": [{"stage": "drag", "names": ["xi_t", "mobility_t"], "caption": "fixed raspberry in the driven periodic box"},
                               {"stage": "diffusion", "names": ["D_t", "D_r", "D_r_three_axis"], "caption": "free raspberry, the same box"}]},
    }
    write("validation/lb_einstein_periodic", m)


einstein_validation()


def periodic_drag_validation():
    """Hasimoto's periodic correction itself: the fixed raspberry of D2a (R = 3.25, xi_bead = 1000)
    in periodic boxes whose fluid a body force drives (a simple cubic array of spheres), the
    mobility U/F against 1/L, whose slope Hasimoto gives as -2.837297/(6 pi eta)."""
    boxes, t_runs, t_window = [16, 24, 32, 40], [300, 600, 1000, 1500], 100
    m = {
        "study": "lb_periodic_drag_box",
        "description": "Validation (docs/validation.md): the fixed raspberry R = 3.25, xi_bead = 1000 (nominal) in periodic boxes 16 ... 40 of the "
                       "deterministic spec 40 fluid driven by a body force 1e-5 along z (Hasimoto's periodic array); F/U (U the fluid's mean "
                       "velocity) becomes steady with the flow profile, in about L^2/(12 nu), long before U itself; runs of "
                       f"{t_runs} t0, the last {t_window} t0 averaged; the mobility U/F against 1/L with its fitted line, whose slope "
                       "Hasimoto gives as -2.837297/(6 pi eta) = -0.031337 M0^-1 t0 sigma.",
        "replicas": 1,
        "grid": {"d": [6.5], "L": boxes, "steps": [round(t / DT) for t in t_runs], "from": [t - t_window for t in t_runs]},
        "zip": [["L", "steps", "from"]],
        "stages": [
            sphere_config(121) | {"params": {**sphere_config(121)["params"], "placement": "centre"}},
            {"name": "lb", "tool": "lb", "inputs": ["config"], "params": {
                "seed": 122, "time_step": DT, "steps": "${grid.steps}", "observe_every": ROW // 2,
                "fluid": {"thermal": False, "warmup_steps": 0, "body_force": [0, 0, 1e-5]},
                "raspberries": {"xi_bead": 1000, "fixed": True}}},
            {"name": "drag", "tool": "lb-drag", "inputs": ["lb"], "params": {"window": {"from": "${grid.from}"}, "blocks": 5}},
        ],
        "report": {"title": "Hasimoto's periodic correction: drag of a fixed raspberry in periodic boxes",
                   "scalars": [{"stage": "drag", "names": ["mobility_t", "xi_t", "R_eff_t"], "caption": "per box"}],
                   "plots": [{"name": "mobility", "stage": "drag", "scalar": "mobility_t", "x": "L", "x_power": -1,
                              "theory": [{"kind": "fit_line", "label": "1/xi_0 + c_1 / L (Hasimoto: c_1 = -0.031337)"}],
                              "xlabel": "1/L (1/sigma)", "ylabel": "U / F (t0/M0)", "title": "Mobility of the fixed raspberry against 1/L"}]},
    }
    write("validation/lb_periodic_drag_box", m)


periodic_drag_validation()


# --- D5: a raspberry sphere in a cylindrical pore (spec 40 §6, §7.3, §9) ----------------------------
R_PORE_RASPBERRY, R_WALL_BEAD = 4.25, 6.25
ETA_SIM = 6.004 * NU_SIM
D0_STOKES = 1.0 / (6 * 3.141592653589793 * ETA_SIM * R_PORE_RASPBERRY)  # kT/(6 pi eta R), R = 4.25


# Spec 70 §7.4's centreline drag K(lambda) (external) at beta = 0 of each pore's S_z curve.
CENTRELINE = [{"kind": "pore_centreline", "formula": f, "radius": R_PORE_RASPBERRY, "columns": ["S_z"]} for f in ("haberman_sayre", "bohlin")]
ABLATION_XI = 1000  # spec 40 §6: the single-layer raspberry at high xi_bead


def pore_panel(smoke):
    """One panel of S_x, S_y, S_z against beta (rows xi_bead, a colour per pore), the ablation over its xi_bead row."""
    return {"name": "S_panel", "stage": "pore", "table": "pore_bins", "x": "beta", "y": [f"S_{a}" for a in "xyz"], "rows": "xi_bead",
            "overlay": {"stage": "pore_single", "label": "single layer (ablation)", "row": ABLATION_XI},
            "xlabel": "beta = d / (R_pore - R)", "ylabel": "S_i = D_0 / D_i^p",
            "title": "Enhanced drag in the pore" + (" (smoke)" if smoke else "") + ": radial S_x, azimuthal S_y, axial S_z",
            "caption": f"Rows xi_bead, columns S_x, S_y, S_z against beta; a colour per pore (lambda = {R_PORE_RASPBERRY} / R_pore). Dashed, "
                       f"open markers: the ablation, the single-layer raspberry at xi_bead = {ABLATION_XI}, over the xi_bead = {ABLATION_XI} "
                       "row. At beta = 0 in the S_z column: the centreline K(lambda) of Haberman-Sayre (stars) and Bohlin (diamonds), "
                       "external (spec 70 §7.4).",
            "theory": CENTRELINE}


def pore_manifest(smoke):
    import math
    if smoke:
        lambdas, xis, l_z, replicas, steps = [0.5], [1000], 24, 2, 20_000
        l_xy = {0.5: 32}
    else:
        lambdas, xis, l_z, replicas, steps = [0.1, 0.2, 0.3, 0.4, 0.5], [50, 200, 1000], 85, 1, 1_200_000 * ROW
        l_xy = {lam: math.ceil(2 * (R_PORE_RASPBERRY / lam + R_WALL_BEAD) + 2) for lam in lambdas}  # spec 40 §6's decision
    pores = [R_PORE_RASPBERRY / lam for lam in lambdas]
    grid = {"R_pore": pores, "L_xy": [l_xy[lam] for lam in lambdas], "xi_bead": xis}
    steps_single = steps // 2 if smoke else steps  # the smoke's ablation: half its runs
    # spec 40 §6: single-layer filled raspberries at high xi_bead in the same pores
    ablation_stages = [
        {"name": "lb_single", "tool": "lb", "inputs": ["config"], "params": {
            "seed": 104, "time_step": DT, "steps": steps_single, "observe_every": 10 * ROW, "frames": {"every_steps": ROW},
            "raspberries": {"xi_bead": ABLATION_XI, "layers": "single"}, "pore": {"radius": "${grid.R_pore}"}}},
        {"name": "pore_single", "tool": "lb-pore", "inputs": ["lb_single"], "params": {"D0": D0_STOKES, "lags": 25, "bin_width": 0.05}}]
    return {
        "study": "lb_pore" + ("-smoke" if smoke else ""),
        "description": ("D5 smoke: " if smoke else "Study D5 (spec 60 D5, spec 40 §6, §7.3, §9; Ustach & Faller): ")
        + "a raspberry sphere R = 4.25 in a cylindrical pore along z (solid nodes beyond R_pore, halfway bounce-back; wall beads r_p = 6.25 "
          "5 nm apart at R_pore + r_p repelling the inner layer by WCA sigma = 6.75), the fluctuating fluid (nu = 0.8, xi_bead nominal); "
          "pore-frame MSDs per beta bin (0.05) over the first 25 recordings and S_i = D_0 / D_i^p (anisodyn-lb-pore). Decision: D_0 is "
          f"the Stokes value kT/(6 pi eta R) = {D0_STOKES:.6g} sigma^2/t0 for R = 4.25 (the study proper divides by D3's extrapolated D_0 at "
          "the same xi_bead, which a manifest cannot pass between studies: rescale S by that ratio). "
        + (f"lambda = 0.5 (R_pore = 8.5), L_xy = 32, L_z = 24 (reduced), xi_bead = 1000, {replicas} runs of {steps} MD steps; the "
           f"single-layer ablation (stages lb_single, pore_single) the same with {steps_single} MD steps per run, drawn over the "
           f"xi_bead = {ABLATION_XI} row of the panel." if smoke else
           f"lambda 0.1 ... 0.5, xi_bead 50, 200, 1000, L_z = {l_z}, L_xy = 2(R_pore + r_p) + 2 rounded up; 1.2 x 10^6 recordings each. "
           "Ablation (spec 40 §6): the single-layer filled raspberry (raspberries.layers single: no outer hydrodynamic-only layer), "
           f"xi_bead = {ABLATION_XI}, in every pore (stages lb_single, pore_single), drawn over the xi_bead = {ABLATION_XI} row of the S "
           "panel (rows xi_bead, columns S_x, S_y, S_z). The S_z column carries the centreline K(lambda) of Haberman-Sayre and Bohlin "
           "at beta = 0 (spec 70 §7.4, external)."),
        "replicas": replicas,
        "grid": grid,
        "zip": [["R_pore", "L_xy"]],
        "stages": [
            {"name": "config", "tool": "config", "replicate": False, "params": {
                "seed": 101, "placement": "centre",
                "species": [{"name": "raspberry", "shape": {"type": "sphere", "diameter": 2 * R_PORE_RASPBERRY}}],
                "composition": [{"species": "raspberry", "count": 1}], "box": {"edges": ["${grid.L_xy}", "${grid.L_xy}", l_z]}}},
            {"name": "lb", "tool": "lb", "inputs": ["config"], "params": {
                "seed": 102, "time_step": DT, "steps": steps, "observe_every": 10 * ROW, "frames": {"every_steps": ROW},
                "raspberries": {"xi_bead": "${grid.xi_bead}"}, "pore": {"radius": "${grid.R_pore}"}}},
            {"name": "pore", "tool": "lb-pore", "inputs": ["lb"], "params": {"D0": D0_STOKES, "lags": 25, "bin_width": 0.05}},
        ] + ablation_stages,
        "report": {
            "title": "D5" + (" smoke" if smoke else "") + ": enhanced drag in a cylindrical pore",
            "scalars": [{"stage": "pore", "names": ["S_*_centreline"], "caption": "S_i of the sub-trajectories starting near the axis (beta < 0.1)"},
                        {"stage": "pore_single", "names": ["S_*_centreline"],
                         "caption": f"ablation (single layer, xi_bead = {ABLATION_XI}): S_i near the axis"}],
            "plots": [pore_panel(smoke)],
        },
    }


for smoke in (True, False):
    write("lb_pore" + ("-smoke" if smoke else ""), pore_manifest(smoke))


# --- D3, D4: diffusion of free raspberries (spec 40 §7.1, §8) -------------------------------------


def hasimoto_plot(name, select, title):
    return {"name": name, "stage": "diffusion", "scalar": "D_t", "x": "L", "x_power": -1, "select": select,
            "theory": [{"kind": "fit_line", "label": "D_t = D_0 + c_1 / L (intercept: D_0)"}],
            "xlabel": "1/L (1/sigma)", "ylabel": "D_t (sigma^2/t0, simulated fluid)", "title": title}


def sphere_sweep_manifest(smoke):
    if smoke:
        grid = {"d": [4.5], "xi_bead": [50], "L": [16, 20, 24]}
        replicas, steps, fit, window_from = 2, 20_000, {"t_min": 4, "t_max": 40}, None
    else:
        pairs = [(2 * r, round(l * r / 4.25)) for r in RADII for l in L_ELLIPSOID]
        grid = {"d": [p[0] for p in pairs], "L": [p[1] for p in pairs], "xi_bead": [50, 200, 1000]}
        replicas, steps, fit, window_from = RUNS, RECORDINGS // RUNS * ROW, None, None
    m = {
        "study": "lb_sphere_radius_sweep" + ("-smoke" if smoke else ""),
        "description": ("D3 smoke: " if smoke else "Study D3 (spec 60 D3, spec 40 §7.1, §8.1-8.2; Ustach & Faller): ")
        + "one free raspberry sphere in a periodic cubic box of the fluctuating D3Q19 fluid (rho = 6.004, nu = 0.8, kT = 1; xi_bead nominal, "
          "scaled by s = 0.8/5.6757), 1000 MD steps of fluid warm-up, recordings every 200 MD steps (2 t0); lab-frame D_t (MSD slope / 6) "
          "and its Hasimoto 1/L extrapolation (the fit line's intercept is D_0), D_r of the reference bead (4 tau estimator), three-axis and "
          "body-axis D_r (anisodyn-lb-diffusion); the report's frictions xi^t = kT/D_0, xi^r = kT/D_r (mean over the boxes) and, with two "
          "radii or more, the calibration lines xi^t = m_t R + b_t, xi^r = m_r R^3 + b_r per xi_bead (spec 40 §8.5). "
        + (f"R = 2.25, xi_bead = 50, boxes 16, 20, 24, {replicas} runs of {steps} MD steps each; the translational fit over lags 4 ... 40 t0 "
           "(spec 40's 0.5 ... 2 L^2/nu is beyond the smoke's runs)." if smoke else
           f"Boxes L = round(L_ell R/4.25) for spec 40 §7.1's eight L_ell (Decision); {RECORDINGS} recordings per box in {RUNS} runs; the "
           "translational fit over spec 40 §8.1's window 0.5 ... 2 L^2/nu."),
        "replicas": replicas,
        "grid": grid,
        "stages": diffusion_stages({"type": "sphere", "diameter": "${grid.d}"}, 81, "${grid.xi_bead}", steps, fit, window_from),
        "report": {
            "title": "D3" + (" smoke" if smoke else "") + ": diffusion of raspberry spheres",
            "scalars": [{"stage": "diffusion", "names": ["D_t", "D_t_hasimoto", "D_r", "D_r_three_axis", "D_r_body_*", "xi_t_over_6pi_eta_R",
                                                         "xi_r_over_8pi_eta_R3"],
                         "caption": "per box: D_t and its Hasimoto-corrected value D_t + 2.837 kT/(6 pi eta L), rotational D_r (run's units)"}],
            "plots": ([hasimoto_plot("D_t_hasimoto_fit", {}, "Finite-size extrapolation of D_t (R = 2.25, xi_bead = 50)")] if smoke else
                      [hasimoto_plot(f"D_t_d{d}_xi{xi}", {"d": d, "xi_bead": xi}, f"Finite-size extrapolation of D_t (R = {d / 2}, xi_bead = {xi})")
                       for d in sorted(set(grid["d"])) for xi in grid["xi_bead"]])
            + [{"name": "D_r_body_axes", "x": "L",
                "series": [{"stage": "diffusion", "scalar": s, "label": s, **({} if smoke else {"select": {"d": 8.5, "xi_bead": 1000}})}
                           for s in ("D_r", "D_r_three_axis", "D_r_body_x", "D_r_body_y", "D_r_body_z")],
                "xlabel": "L (sigma)", "ylabel": "D_r (1/t0)", "title": "Rotational diffusion: lab estimators and the body axes"
                + ("" if smoke else " (R = 4.25, xi_bead = 1000)")}],
            "raspberry": {"stage": "diffusion", "box": "L", "calibration": {"fit": "xi_bead"}},
        },
    }
    if not smoke:
        m["zip"] = [["d", "L"]]
    return m


def spheroid(phi):
    """Semi-axes (a, b, b) of the constant-volume spheroid of aspect phi = a/b (spec 40 §5.3)."""
    return [4.25 * phi ** (2 / 3), 4.25 * phi ** (-1 / 3), 4.25 * phi ** (-1 / 3)]


PHIS = [(1, 10), (1, 5), (1, 4), (1, 3), (1, 2), (2, 3), (4, 5), (9, 10), (10, 9), (5, 4), (3, 2), (2, 1), (3, 1), (4, 1), (5, 1), (10, 1)]


def ellipsoid_manifest(smoke):
    if smoke:
        phis, boxes, replicas, steps, fit = [(2, 1)], [24], 2, 20_000, {"t_min": 4, "t_max": 40}
    else:
        phis, boxes, replicas, steps, fit = PHIS, L_ELLIPSOID, RUNS, RECORDINGS // RUNS * ROW, None
    pairs = [(n / d, l) for n, d in phis for l in boxes if l >= 2 * spheroid(n / d)[0] + 4]  # drop L < 2a + 4 (spec 60 D4)
    dropped = [(f"{n}/{d}", l) for n, d in phis for l in boxes if l < 2 * spheroid(n / d)[0] + 4]
    # phi itself is no parameter of any stage: the plots draw against it as (a/4.25)^(3/2).
    grid = {"a": [spheroid(p[0])[0] for p in pairs], "b": [spheroid(p[0])[1] for p in pairs], "L": [p[1] for p in pairs]}
    shape = {"type": "ellipsoid", "semi_axes": ["${grid.a}", "${grid.b}", "${grid.b}"]}
    ratio_plots = [{"name": f"{kind}_anisotropy", "stage": "diffusion", "scalar": f"D_{kind}_axial_over_perp",
                    "x": "a", "x_scale": 1 / 4.25, "x_power": 1.5,
                    "theory": [{"kind": "spheroid", "factor": f"{kind}_ratio",
                                "label": ("Happel-Brenner" if kind == "t" else "Perrin") + f" {kind}_perp/{kind}_ax"}],
                    "xlabel": "phi = a/b", "ylabel": f"D_{kind},ax / D_{kind},perp (body frame)",
                    "title": ("Translational" if kind == "t" else "Rotational") + " anisotropy in the body frame"}
                   for kind in ("t", "r")]
    if not smoke:
        for p in ratio_plots:
            p["select"] = {"L": 94}
    return {
        "study": "lb_ellipsoid_sweep" + ("-smoke" if smoke else ""),
        "description": ("D4 smoke: " if smoke else "Study D4 (spec 60 D4, spec 40 §5.3, §8.3-8.6; Ustach & Faller): ")
        + "one free constant-volume raspberry spheroid (a b^2 = 4.25^3, symmetry axis along body x) in the fluctuating fluid, xi_bead = 1000 "
          "nominal; body-frame D_t,i and D_r,i by quaternion projection (anisodyn-lb-diffusion), their anisotropies D_ax/D_perp against "
          "Happel-Brenner and Perrin (spec 40 §8.6; no radius calibration needed). "
        + (f"phi = 2 (a = 6.746, b = 3.373), box 24, {replicas} runs of {steps} MD steps; the translational fit over lags 4 ... 40 t0; the report's factors A, B, "
           "E-L invert the Stokes lines 6 pi eta R and 8 pi eta R^3 (no calibration) with D_0 from Hasimoto's slope at the one box."
           if smoke else
           f"The 16 aspect ratios of spec 40 §5.3, boxes of spec 40 §7.1 without those below 2a + 4 (dropped: {dropped}); {RECORDINGS} "
           f"recordings per box in {RUNS} runs. The report inverts D3's calibration lines at xi_bead = 1000 "
           "(results/lb_sphere_radius_sweep/report/raspberry_calibration.json: run D3 first) into the factors A, B, E-L (spec 40 §8.5-8.6)."),
        "replicas": replicas,
        "grid": grid,
        "zip": [["a", "b", "L"]],
        "stages": diffusion_stages(shape, 91, 1000, steps, fit, None),
        "report": {
            "title": "D4" + (" smoke" if smoke else "") + ": diffusion of raspberry spheroids",
            "scalars": [{"stage": "diffusion", "names": ["D_t_body_*", "D_r_body_*", "D_t_axial_over_perp", "D_r_axial_over_perp", "alpha"],
                         "caption": "body-frame diffusion coefficients (run's units) and their anisotropies"}],
            "plots": ratio_plots,
            "raspberry": {"stage": "diffusion", "box": "L", "calibration": "stokes" if smoke else
                          {"file": "lb_sphere_radius_sweep/report/raspberry_calibration.json", "xi_bead": 1000}},
        },
    }


# --- D0: the analytic checks (no fluid) ----------------------------------------------------------
def analytic_checks_manifest(smoke):
    return {
        "study": "lb_analytic_checks" + ("-smoke" if smoke else ""),
        "description": ("D0 smoke, the study itself: " if smoke else "Study D0 (spec 60 D0): ")
        + "the LB analysis without a fluid (anisodyn-lb-checks, suite analytic): synthetic Brownian bodies of known body-frame D_t,i "
          "and D_r,i (D_par != D_perp, the reference vector 0.9 rad from the axis; and a sphere) through anisodyn-lb-diffusion's lag "
          "curves at one interval: the lab MSD, the single-vector estimator (2[D_par sin^2 a + D_perp(1 + cos^2 a)], a sphere's 4 D_r), "
          "the three-axis sum, the body-frame MSD and the projection method per axis, and the paper conventions' 2/3; free Brownian "
          "motion from a disk through the pore-frame transform (S = 1 from beta = 0.2); the spheroid nearest-point bisection against "
          "brute force; the reduced units in SI against spec 70 §7.1; and in the report the spheroid factors A, B, E-L against spec 70 "
          "§7.3's table (within 1e-4 or half a unit of the last printed digit) with its identities (harmonic and rotational means, disk "
          "and sphere limits). 300 bodies of 1500 intervals per case; seconds.",
        "replicas": 1,
        "stages": [{"name": "checks", "tool": "lb-checks", "params": {"suite": "analytic", "seed": 17}}],
        "report": {
            "title": "D0" + (" smoke" if smoke else "") + ": analytic checks of the LB analysis",
            "scalars": [{"stage": "checks", "names": ["synthetic_*"],
                         "caption": "synthetic bodies: measured over expected (target 1; the paper conventions 2/3)"},
                        {"stage": "checks", "names": ["pore_frame_worst_pull", "nearest_point_*"],
                         "caption": "pore frame (largest pull, Gaussian: about 3 at most) and the nearest-point bisection (target: round-off)"},
                        {"stage": "checks", "names": ["unit_*"], "caption": "reduced units in SI: relative difference from spec 70 §7.1's printed values"}],
            "plots": [{"name": "pore_frame", "stage": "checks", "table": "pore_frame_free", "x": "beta", "y": ["S_x", "S_y", "S_z"],
                       "theory": [{"kind": "constant", "value": 1, "label": "free motion: S = 1"}],
                       "xlabel": "beta = d/(R_pore - R)", "ylabel": "S_i = 2D / <dx_i^2>", "title": "Pore-frame transform of free motion"}],
            "spheroid_reference": {"tolerance": 1e-4},
        },
    }


write("lb_analytic_checks-smoke", analytic_checks_manifest(True))
write("lb_analytic_checks", analytic_checks_manifest(False))


# --- D1: the fluid checks (spec 40 §2.5, §3) -----------------------------------------------------
def fluid_checks_manifest(smoke):
    lb_steps = 5000 if smoke else 50_000
    return {
        "study": "lb_fluid_checks" + ("-smoke" if smoke else ""),
        "description": ("D1 smoke: " if smoke else "Study D1 (spec 60 D1, spec 40 §2.5 and §3): ")
        + "the checks of the LB fluid in lattice units at spec 40's parameters (rho = 6.004, nu = 0.016, i.e. 0.8 sigma^2/t0, kT = 4e-4; "
          "anisodyn-lb-checks): every mode's mean square and <u^2> per node against mu rho b_k and kT/rho on a 24^3 lattice "
          f"({lb_steps} LB steps after 1000 of warm-up, 10 blocks); the viscosity from shear-wave decay at nu = 0.016, water's 0.1135 and "
          "tau = 1; plug flow between walls moving together at 2.20 m/s; total momentum and mass with 16 free beads point-coupled to the "
          "thermal fluid (xi = 0.56, m = 10) and their temperature; a bead pulled through a 12^3 fluid against Ahlrichs-Dunweg's "
          "1/xi + 1/(25 eta a), at a node, a cell centre, an off-lattice point and averaged over 16 random points, with spec 40's coupling "
          "velocity u = (j + f/2)/rho and with Ahlrichs-Dunweg's u = j/rho. "
        + ("Spec 60's smoke size: a block (500 steps) is shorter than the slowest relaxation (912 steps), so the mode errors are too small."
           if smoke else "Decision: 5e4 LB steps, so that a block spans five slowest relaxations (912 steps) and the block errors hold."),
        "replicas": 1,
        "stages": [{"name": "checks", "tool": "lb-checks", "params": {"box": 24, "lb_steps": lb_steps, "seed": 11}}],
        "report": {
            "title": "D1" + (" smoke" if smoke else "") + ": checks of the LB fluid",
            "scalars": [{"stage": "checks", "names": ["u2_ratio", "worst_mode_pull", "shear_wave_*", "plug_flow_deviation", "momentum_change",
                                                      "mass_change", "bead_temperature"],
                         "caption": "thermalisation, viscosity, plug flow, conservation with beads (targets: 1, < 3, 1, 0, round-off, round-off, "
                                    "1/(1 - xi h/2m) = 1.0142)"},
                        {"stage": "checks", "names": ["mobility_over_AD_*"],
                         "caption": "pulled bead's mobility over Ahlrichs-Dunweg's formula with g = 25 (the g measured is in the details)"}],
            "plots": [{"name": "modes", "stage": "checks", "table": "modes", "x": "mode", "y": ["ratio"],
                       "theory": [{"kind": "constant", "value": 1, "label": "target (mu rho b_k; kT/rho for u)"}],
                       "xlabel": "mode k (19: u per component)", "ylabel": "<m_k^2> / target", "title": "Thermalisation of every mode"},
                      {"name": "bead_mobility", "stage": "checks", "table": "bead_mobility", "x": "node_distance",
                       "y": ["ratio_half_force", "ratio_momentum_only"],
                       "theory": [{"kind": "constant", "value": 1, "label": "Ahlrichs-Dunweg, g = 25"}],
                       "xlabel": "distance of the bead from the nearest node centre", "ylabel": "mobility / Ahlrichs-Dunweg's",
                       "title": "Pulled bead: u = (j + f/2)/rho (spec 40) and u = j/rho"}],
        },
    }


write("lb_fluid_checks-smoke", fluid_checks_manifest(True))
write("lb_fluid_checks", fluid_checks_manifest(False))


# --- D6: the viscosity scaling of spec 40 §1.1 ---------------------------------------------------
NU_WATER = 5.6757


def viscosity_manifest(smoke):
    # The water fluid takes xi_bead unscaled (s = 1). At dt = 0.01 its dt sum(xi)/m is 1/s = 7.1 times
    # the scaled run's (2.85 for R = 4.25: the explicit coupling diverges; anisodyn-lb refuses it), so
    # the water runs take dt = s * 0.01 (2/1420 t0, so that a recording is 1420 steps = 2 t0): the same
    # stability number and lattice relaxation time as the scaled runs, over the same simulated time.
    frame_steps = [1420, ROW]  # even (whole LB steps), within 0.1% of 2 t0 / (s 0.01)
    dts = [2.0 / frame_steps[0], DT]
    if smoke:
        t_run, boxes, replicas, fit = 20.0, [24], 2, {"t_min": 2, "t_max": 10}
    else:
        t_run, boxes, replicas, fit = RECORDINGS // RUNS * ROW * DT, [32, 48, 64], RUNS, None
    grid = {"nu": [NU_WATER, NU_SIM], "dt": dts, "steps": [round(t_run / dt) for dt in dts], "frame_steps": frame_steps,
            "warmup": [5 * n for n in frame_steps], "L": boxes}
    stages = diffusion_stages({"type": "sphere", "diameter": 8.5}, 101, 1000, "${grid.steps}", fit, None)
    lb = stages[1]["params"]
    lb.update({"time_step": "${grid.dt}", "observe_every": "${grid.frame_steps}", "frames": {"every_steps": "${grid.frame_steps}"},
               "fluid": {"viscosity": "${grid.nu}", "warmup_steps": "${grid.warmup}"}})
    return {
        "study": "lb_viscosity_scaling" + ("-smoke" if smoke else ""),
        "description": ("D6 smoke: " if smoke else "Study D6 (spec 60 D6, spec 40 §1.1; Ustach & Faller): ")
        + "one free raspberry sphere R = 4.25 (xi_bead = 1000 nominal) in the fluctuating fluid of water's viscosity nu = 5.6757 (xi_bead "
          "unscaled, s = 1) and of spec 40's nu = 0.8 (xi_bead scaled by s = 0.8/5.6757); the frictions xi^t/(6 pi eta R) (D_0 from the "
          "Hasimoto line over the boxes) and xi^r/(8 pi eta R^3) in each fluid's own units (the ratios are the same in water units), "
          "and the stability number dt sum(xi_bead)/m of each run. Decision: at dt = 0.01 the water run's stability number is 2.85 "
          "(the coupling diverges), so the water runs take dt = 2/1420 t0 (s 0.01 within 0.1%), the same stability number and lattice "
          "relaxation time as the scaled runs, over the same simulated time (7.1 times the steps); warm-up 10 t0 in both. "
        + (f"Box 24, {replicas} runs of {t_run:g} t0 per fluid; D_0 from Hasimoto's slope at the one box; the translational fit "
           "over lags 2 ... 10 t0." if smoke else
           f"Boxes 32, 48, 64; {RECORDINGS} recordings (2 t0 each) per box in {RUNS} runs (Decision: D3's run length); the translational fit over "
           "spec 40 §8.1's window 0.5 ... 2 L^2/nu."),
        "replicas": replicas,
        "grid": grid,
        "zip": [["nu", "dt", "steps", "frame_steps", "warmup"]],
        "stages": stages,
        "report": {
            "title": "D6" + (" smoke" if smoke else "") + ": viscosity scaling",
            "scalars": [{"stage": "diffusion", "names": ["D_t", "D_r", "xi_t_over_6pi_eta_R", "xi_r_over_8pi_eta_R3", "xi_t_water",
                                                         "xi_r_water", "stability"],
                         "caption": "per fluid and box: D (run's units), the Stokes ratios of the box, frictions in water units, "
                                    "dt sum(xi_bead)/m"}],
            "plots": [{"name": f"{kind}_ratio_bars", "stage": "diffusion", "scalar": scalar, "groups": "L", "bars": "nu",
                       "theory": [{"kind": "constant", "value": 1, "label": label}],
                       "xlabel": "box edge L (nm)", "ylabel": ylabel,
                       "title": f"{'Translational' if kind == 't' else 'Rotational'} friction per box: water (nu = {NU_WATER}, xi unscaled) "
                                f"and nu = {NU_SIM} (xi scaled)",
                       "caption": f"Paired bars per box: nu = {NU_WATER} is water (xi_bead unscaled), nu = {NU_SIM} spec 40's fluid "
                                  "(xi_bead scaled by s); the ratios are the same in water units. Error bars: the standard errors."}
                      for kind, scalar, label, ylabel in (("t", "xi_t_over_6pi_eta_R", "Stokes", "xi^t / (6 pi eta R)"),
                                                          ("r", "xi_r_over_8pi_eta_R3", "SED", "xi^r / (8 pi eta R^3)"))],
            "raspberry": {"stage": "diffusion", "box": "L"},
        },
    }


write("lb_viscosity_scaling-smoke", viscosity_manifest(True))
write("lb_viscosity_scaling", viscosity_manifest(False))

def hasimoto_free_sphere_validation():
    """D3 at one radius and reduced length: a free raspberry sphere R = 2.25 (xi_bead = 50) in boxes 12, 16, 24 of a fluid
    ten times as viscous as spec 40's, 4 runs of 1e4 t0 each, D_t over spec 40's window 0.5 ... 2 L^2/nu: the Hasimoto
    line's slope and D_0."""
    boxes, nu = [12, 16, 24], 8
    tau = 0.5 + 3 * 0.016 * nu / NU_SIM  # lattice relaxation time (nu = 0.8 is 0.016 in lattice units, D1)
    m = sphere_sweep_manifest(False)
    m.update({"study": "lb_hasimoto_free_sphere", "grid": {"d": [4.5], "xi_bead": [50], "L": boxes}, "replicas": 4})
    del m["zip"]
    m["stages"] = diffusion_stages({"type": "sphere", "diameter": "${grid.d}"}, 121, "${grid.xi_bead}", 1_000_000, None, None)
    m["stages"][1]["params"]["fluid"] = {"viscosity": nu}
    m["description"] = ("Validation (docs/validation.md): the finite-size law of spec 40 §8.1 for a free raspberry sphere, R = 2.25, "
                        f"xi_bead = 50 nominal, in periodic boxes {', '.join(map(str, boxes))} of the fluctuating fluid (rho = 6.004, "
                        f"nu = {nu}, kT = 1), 4 runs of 1e4 t0 per box; D_t over spec 40's window 0.5 ... 2 L^2/nu; the report's Hasimoto "
                        "line of D_t against 1/L (its slope against -2.837297 kT/(6 pi eta)) and D_0, and D_r over the boxes. nu is ten "
                        f"times spec 40's {NU_SIM} (lattice tau {tau:.2f}): the window, and so the error of D_t at a given run length, "
                        "shrinks by sqrt(10), while the Hasimoto correction 2.837 R_h/L does not depend on nu.")
    m["report"] = {"title": "Validation: D_t(L) of a free raspberry sphere", "scalars": m["report"]["scalars"],
                   "plots": [hasimoto_plot("D_t_hasimoto_fit", {}, "Finite-size extrapolation of D_t (R = 2.25, xi_bead = 50)")],
                   "raspberry": {"stage": "diffusion", "box": "L"}}
    write("validation/lb_hasimoto_free_sphere", m)


hasimoto_free_sphere_validation()

for smoke in (True, False):
    write("lb_sphere_radius_sweep" + ("-smoke" if smoke else ""), sphere_sweep_manifest(smoke))
    write("lb_ellipsoid_sweep" + ("-smoke" if smoke else ""), ellipsoid_manifest(smoke))


write("lb_bead_resistance_sweep-smoke", resistance_manifest(True))  # spec 60 D2: the smoke is D2a only
full_resistance = resistance_manifest(False)
add_diffusion_half(full_resistance)
write("lb_bead_resistance_sweep", full_resistance)
