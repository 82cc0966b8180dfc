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


def write(name, manifest):
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(manifest, f, indent=2, ensure_ascii=False)
        f.write("\n")


def sphere_config(seed):
    return {"name": "config", "tool": "config", "replicate": False, "params": {
        "seed": seed, "placement": "lattice",
        "species": [{"name": "raspberry", "shape": {"type": "sphere", "diameter": "${grid.d}"}}],
        "composition": [{"species": "raspberry", "count": 1}],
        "box": {"edges": ["${grid.L}"] * 3}}}


# --- D2a: Stokes-flow drag of a fixed raspberry sphere (spec 40 §7.2) -------------------------------
def resistance_manifest(smoke):
    if smoke:
        grid = {"d": [6.5], "xi_bead": [50, 1000], "L": [32]}
        t_run, t_window, blocks = 60, 20, 5
    else:
        grid = {"d": [6.5, 11.5], "xi_bead": [10, 25, 50, 100, 200, 400, 600, 800, 1000], "L": [40, 50, 64]}
        t_run, t_window, blocks = 2000, 200, 10
    steps = round(t_run / DT)
    return {
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
           f"(over 15 decay times L^2/(4 pi^2 nu) of the largest box), the last {t_window} t0 (100 recordings) averaged. The diffusion part "
           "D2b is not in this manifest yet."),
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


for smoke in (True, False):
    write("lb_bead_resistance_sweep" + ("-smoke" if smoke else ""), resistance_manifest(smoke))
