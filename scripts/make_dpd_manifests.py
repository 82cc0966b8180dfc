#!/usr/bin/env python3
"""Writes the C4 and C5 manifests (spec 60: dpd_sphere_diffusion, dpd_rod_diffusion and their
smokes) from Table S1 and the Tirado-Garcia de la Torre equivalent diameters (spec 30 §10), so that
the per-system x and y scales of the reduced plots follow from the formulas, not by hand.
Also C2 and C3 (dpd_slip_length, dpd_flow_fixed_sphere). Run from anywhere: scripts/make_dpd_manifests.py"""
import json
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "manifests")
C = (math.pi / 6) ** (1 / 3)
ETA = 2.591  # C1 on this machine (docs/validation.md, "DPD viscosity": weighted mean of L_box 3-8)
LIQ = {"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}
TABLE_S1 = {
    "sphere": {1: [4, 5, 6, 8, 12, 20], 2: [4, 5, 6, 8, 12, 20], 3: [5, 6, 8, 12, 20], 4: [6, 8, 12, 20], 5: [8, 12, 20], 6: [8, 12, 20]},
    "rod": {(1, 2): [4, 5, 6, 8, 12, 20], (1, 3): [5, 6, 8, 12, 20], (1, 4): [6, 8, 12, 20], (1, 5): [8, 12, 20], (1, 6): [8, 12, 20],
            (2, 4): [6, 8, 12, 20], (2, 5): [8, 12, 20], (2, 6): [8, 12, 20], (3, 6): [8, 12, 20]}}


def tgdlt(d, L):
    p = L / d
    nu_t = 0.312 + 0.565 / p - 0.100 / p ** 2
    nu_r = -0.662 + 0.917 / p - 0.050 / p ** 2
    return L / (math.log(p) + nu_t), L / (3 * (math.log(p) + nu_r)) ** (1 / 3)


def stages(colloid_shape, frames_time, t_run, window_from, fit, rod):
    name = "rod" if rod else "sphere"
    st = [
        {"name": "config", "tool": "config", "params": {
            "seed": 41, "placement": "colloids_in_liquid",
            "species": [{"name": name, "shape": colloid_shape}, LIQ],
            "composition": [{"species": name, "count": 1}],
            "liquid": {"species": "liquid", "density": 3},
            "box": {"edges": ["${grid.L_box}"] * 3}}},
        {"name": "dpd", "tool": "dpd", "inputs": ["config"], "params": {
            "seed": 42, "time_step": 0.005, "time": t_run, "observe_every": 1000,
            "liquid": {"a": 25, "gamma": 100},
            "colloids": {"species": [name], "gamma_surface": "${grid.gamma_ls0}"},
            "frame_species": [name], "frames": {"every_time": frames_time}}},
        {"name": "msd", "tool": "msd", "inputs": ["dpd"], "params": {
            "species": name, "window": {"from": window_from}, "fit": fit,
            **({"reference": "particle_axis", "body_frame": True} if rod else {})}},
    ]
    if rod:
        st.append({"name": "rotation", "tool": "rotation", "inputs": ["dpd"], "params": {"axes": ["L"], "window": {"from": window_from}, "fit": fit}})
    return st


def sphere_manifest(smoke):
    if smoke:
        grid = {"d": [2], "L_box": [6], "gamma_ls0": [0, 10 / 3]}
        zip_ = None
        reps, t_run, win, fit = 4, 200, 100, {"t_min": 1, "t_max": 10}
    else:
        pairs = [(d, L) for d, Ls in TABLE_S1["sphere"].items() for L in Ls]
        grid = {"d": [p[0] for p in pairs], "L_box": [p[1] for p in pairs], "gamma_ls0": [0, 10 / 3, 20 / 3, 10, 50 / 3, 100 / 3]}
        zip_ = [["d", "L_box"]]
        reps, t_run, win, fit = 200, 1000, 500, {"t_min": 10, "t_max": 100}
    shape = {"type": "sphere", "diameter": "${grid.d}"}
    ds = sorted(set(grid["d"]))
    series = [{"stage": "msd", "scalar": "D_tot_sphere", "select": {"d": d, "gamma_ls0": g}, "x_scale": 1 / (C * d), "y_scale": ETA * d,
               "label": f"d = {d}, gamma_ls0 = {g:.4g}"} for d in ds for g in grid["gamma_ls0"]]
    m = {
        "study": "dpd_sphere_diffusion" + ("-smoke" if smoke else ""),
        "description": ("C4 smoke: " if smoke else "Study C4 (spec 60, spec 30 §3.1, §5, §9-10; Liu & Widmer-Cooper): ")
        + "a density-matched DPD sphere (point mass rho pi d^3/6, Mie(50,49) core, friction shell delta = 0.5 with surface friction gamma_ls0, vector3d shell noise) "
          "at the centre of a periodic box of liquid (rho = 3, a = 25, gamma = 100, dt = 0.005; N_liquid = round(3 (L^3 - pi d^3/6)) placed uniformly outside the sphere, "
          "Maxwell-Boltzmann at kT = 1, sphere at rest); " + (f"d = 2, L_box = 6, {reps} trajectories x {t_run} tau, the last {t_run - win} tau analysed" if smoke else
          f"Table S1's 27 (d, L_box) systems x gamma_ls0, {reps} trajectories x {t_run} tau each, the last {t_run - win} tau analysed")
        + f"; sphere frames every {0.05} tau (liquid not stored); D_t from the MSD over all time origins, linear fit t = {fit['t_min']} ... {fit['t_max']} tau; "
          f"reduced D_bar_t = D_t eta d with the measured C1 viscosity eta = {ETA} (docs/validation.md) against phi^(1/3) = (pi/6)^(1/3) d/L_box, "
          "with Hasimoto's stick Q(phi)/(3 pi) and slip Q Q'/(3 pi) lines and +-20% bands (spec 30 §10).",
        "replicas": reps,
        "grid": grid,
        "stages": stages(shape, 0.05, t_run, win, fit, rod=False),
        "report": {
            "title": "C4" + (" smoke" if smoke else "") + ": sphere diffusion in the DPD liquid",
            "scalars": [{"stage": "msd", "names": ["D_tot_sphere"], "caption": f"D_t of the sphere (fit {fit['t_min']} ... {fit['t_max']} tau), in r_c^2/tau"}],
            "plots": [{"name": "reduced_D_t", "x": "L_box", "x_power": -1, "series": series,
                       "theory": [{"kind": "hasimoto", "boundary": "stick", "band": 0.2}, {"kind": "hasimoto", "boundary": "slip", "band": 0.2}],
                       "xlabel": "phi^(1/3)", "ylabel": f"D_bar_t = D_t eta d (eta = {ETA})",
                       "title": "Reduced sphere diffusion against periodic-box theory"}]}}
    if zip_:
        m["zip"] = zip_
    return m


def rod_manifest(smoke):
    if smoke:
        rods = [(1, 4)]
        pairs = [(1, 4, 6)]
        grid = {"d": [1], "cylinder": [3], "L_box": [6], "gamma_ls0": [20 / 3]}
        zip_ = None
        reps, t_run, win, fit = 4, 200, 100, {"t_min": 1, "t_max": 10}
    else:
        pairs = [(d, L, Lb) for (d, L), Lbs in TABLE_S1["rod"].items() for Lb in Lbs]
        grid = {"d": [p[0] for p in pairs], "cylinder": [p[1] - p[0] for p in pairs], "L_box": [p[2] for p in pairs], "gamma_ls0": [0, 10 / 3, 20 / 3]}
        zip_ = [["d", "cylinder", "L_box"]]
        reps, t_run, win, fit = 200, 1000, 500, {"t_min": 10, "t_max": 100}
        rods = list(TABLE_S1["rod"])
    shape = {"type": "spherocylinder", "length": "${grid.cylinder}", "diameter": "${grid.d}"}
    series_t, series_r, series_p = [], [], []
    for d, L in rods:
        largest_box = max(Lb for dd, LL, Lb in pairs if (dd, LL) == (d, L))
        for g in grid["gamma_ls0"]:
            series_p.append({"stage": "msd", "scalar": "D_body_par_over_perp_rod", "at_x": L / d,
                             "select": {"d": d, "cylinder": L - d, "L_box": largest_box, "gamma_ls0": g},
                             "label": f"({d},{L}), L_box = {largest_box}, gamma_ls0 = {g:.4g}"})
        dt_, dr_ = tgdlt(d, L)
        for g in grid["gamma_ls0"]:
            sel = {"d": d, "cylinder": L - d, "gamma_ls0": g}
            lab = f"({d},{L}), gamma_ls0 = {g:.4g}"
            series_t.append({"stage": "msd", "scalar": "D_tot_rod", "select": sel, "x_scale": 1 / (C * dt_), "y_scale": ETA * dt_, "label": lab})
            series_r.append({"stage": "rotation", "scalar": "Dr_msad_L_rod", "select": sel, "x_scale": 1 / (C * dr_), "y_scale": ETA * dr_ ** 3, "label": lab})
    m = {
        "study": "dpd_rod_diffusion" + ("-smoke" if smoke else ""),
        "description": ("C5 smoke: " if smoke else "Study C5 (spec 60, spec 30 §3.2, §5, §9-10; Liu & Widmer-Cooper): ")
        + "a density-matched rigid DPD rod (spheres of diameter d spaced 0.5 on L - d, each of mass 3 V/N_s; a linear rotor; Mie(50,49) cores, friction shells "
          "delta = 0.5 with surface friction gamma_ls0 at the site centres' rigid-body velocities, vector3d shell noise) at the centre of a periodic box of liquid "
          "(rho = 3, a = 25, gamma = 100, dt = 0.005; N_liquid = round(3 (L_box^3 - V_rod)) placed uniformly outside the rod; rod at rest, random axis); "
        + ("rod (1,4) (cylinder L - d = 3), L_box = 6" if smoke else "Table S1's 34 (d, L, L_box) systems x gamma_ls0")
        + f", {reps} trajectories x {t_run} tau, the last {t_run - win} tau analysed; rod frames every 0.05 tau (liquid not stored); "
          f"D_t, D_par, D_perp (lab frame to the axis at the time origin, and body frame) from the MSD, D_r from the MSAD of the unbounded rotation vector "
          f"(4 D_r t), linear fits t = {fit['t_min']} ... {fit['t_max']} tau; reduced D~_t = D_t eta d_t and D~_r = D_r eta d_r^3 with the Tirado-Garcia de la Torre "
          f"equivalent diameters and the measured C1 viscosity eta = {ETA} (docs/validation.md), against phi_t^(1/3) and phi_r^(1/3) with Q(phi_t)/(3 pi) and "
          "(1 - phi_r)/pi and +-20% bands (spec 30 §10).",
        "replicas": reps,
        "grid": grid,
        "stages": stages(shape, 0.05, t_run, win, fit, rod=True),
        "report": {
            "title": "C5" + (" smoke" if smoke else "") + ": rod diffusion in the DPD liquid",
            "scalars": [{"stage": "msd", "names": ["D_tot_rod", "D_par_rod", "D_perp_rod", "D_body_z_rod", "D_body_x_rod",
                                                   "D_par_over_D_perp_rod", "D_body_par_over_perp_rod"],
                         "caption": "D_t, D_par, D_perp (lab frame, to the axis at the time origin) and the body-frame D_par (body_z), D_perp (body_x), "
                                    "r_c^2/tau; D_par/D_perp in the lab and the body frame"},
                        {"stage": "rotation", "names": ["Dr_msad_L_rod", "Dr_C1_L_rod"], "caption": "D_r of the rod axis from the MSAD (4 D_r t) and from C1, 1/tau"}],
            "plots": [
                {"name": "reduced_D_t", "x": "L_box", "x_power": -1, "series": series_t,
                 "theory": [{"kind": "hasimoto", "boundary": "stick", "band": 0.2}],
                 "xlabel": "phi_t^(1/3)", "ylabel": f"D~_t = D_t eta d_t (eta = {ETA})", "title": "Reduced translational diffusion of the rod"},
                {"name": "reduced_D_r", "x": "L_box", "x_power": -1, "series": series_r,
                 "theory": [{"kind": "periodic_rotation", "band": 0.2}],
                 "xlabel": "phi_r^(1/3)", "ylabel": f"D~_r = D_r eta d_r^3 (eta = {ETA})", "title": "Reduced rotational diffusion of the rod"},
                {"name": "anisotropy_vs_p", "series": series_p, "theory": [{"kind": "tirado_ratio"}],
                 "xlabel": "p = L/d", "ylabel": "D_par/D_perp (body frame)", "title": "Translational anisotropy against aspect ratio"}]}}
    if not smoke:
        # Spec 30 §10's slip-rod comparison: for gamma_ls0 = 0 and d >= 2, D_t / D_t^{SE,slip}(d_t) = D_t 2 pi eta d_t
        # against phi_t^(1/3), with the fitted line c0 + c1 phi_t^(1/3).
        series_slip = []
        for d, L in rods:
            if d < 2:
                continue
            dt_, _ = tgdlt(d, L)
            series_slip.append({"stage": "msd", "scalar": "D_tot_rod", "select": {"d": d, "cylinder": L - d, "gamma_ls0": 0},
                                "x_scale": 1 / (C * dt_), "y_scale": 2 * math.pi * ETA * dt_, "label": f"({d},{L})"})
        m["report"]["plots"].append(
            {"name": "slip_rods", "x": "L_box", "x_power": -1, "series": series_slip, "theory": [{"kind": "fit_line"}],
             "xlabel": "phi_t^(1/3)", "ylabel": f"D_t / D_t^(SE,slip)(d_t) = 2 pi eta d_t D_t (eta = {ETA})",
             "title": "Slip rods (gamma_ls0 = 0, d >= 2) and the fitted line c0 + c1 phi_t^(1/3)"})
    if zip_:
        m["zip"] = zip_
    return m


for name, m in (("dpd_sphere_diffusion-smoke", sphere_manifest(True)), ("dpd_sphere_diffusion", sphere_manifest(False)),
                ("dpd_rod_diffusion-smoke", rod_manifest(True)), ("dpd_rod_diffusion", rod_manifest(False))):
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(m, f, indent=2)
        f.write("\n")


# --- C2 (slip length, Couette) and C3 (fixed sphere in flow): spec 30 §6, §8 -------------------------
def couette_manifest(smoke):
    gammas = [0, 10 / 3] if smoke else [0, 1, 2, 10 / 3, 5, 20 / 3, 10]
    forces = [0.05] if smoke else [0.001, 0.0025, 0.005, 0.01, 0.025, 0.05]
    t_eq, t_avg = (100, 100) if smoke else (2000, 20000)
    walls = {"type": "flat_mie", "height": 8, "gamma_surface": ["${grid.gamma_ls0}", 0]}
    m = {
        "study": "dpd_slip_length" + ("-smoke" if smoke else ""),
        "description": ("C2 smoke: " if smoke else "Study C2 (spec 60, spec 30 §6; Liu & Widmer-Cooper): ")
        + "Couette slip length of the DPD liquid (rho = 3, a = 25, gamma = 100, dt = 0.005) between flat Mie(50,49) walls at z = 0 "
          "(friction shell delta = 0.5 with surface friction gamma_ls0, vector3d noise) and z = 8 (perfect slip: Mie only); box 8 x 8 x 9.5 "
          "(periodic in x, y; 1.5 of empty space above the top wall so that no DPD pair crosses z), N = 3 x 8^3 = 1536 placed uniformly "
          "in 0 <= z <= 8; a force f x on every particle with z > 6; "
          f"{t_eq} tau to steady state, then {t_avg} tau averaged (window from {t_eq}); v_x(z) in slabs of 0.1, "
          "slip length b = a/G of the line v_x = G z + a over z = 1.5 ... 5 (b > 0: slip), apparent shear rate v_top/8 with v_top "
          "the mean v_x in 7 <= z < 8; jackknife errors over 10 blocks of the window. "
          + ("gamma_ls0 = 0 (perfect slip at both walls: no steady state, the liquid accelerates, so b is large and poorly defined) and 10/3, f = 0.05 (five times the spec smoke's 0.01, whose 100 tau average leaves b uncertain by 0.4-1 r_c)."
             if smoke else "Grid of spec 30 §6 (Decision)."),
        "replicas": 1,
        "grid": {"gamma_ls0": gammas, "f": forces},
        "stages": [
            {"name": "config", "tool": "config", "replicate": False, "params": {
                "seed": 51, "placement": "colloids_in_liquid",
                "species": [LIQ], "liquid": {"species": "liquid", "density": 3, "z_range": [0, 8]}, "box": {"edges": [8, 8, 9.5]}}},
            {"name": "dpd", "tool": "dpd", "inputs": ["config"], "params": {
                "seed": 52, "time_step": 0.005, "time": t_eq + t_avg, "observe_every": 1000,
                "liquid": {"a": 25, "gamma": 100}, "walls": walls,
                "drive": {"force": ["${grid.f}", 0, 0], "z_min": 6}, "profiles": {"z_bin": 0.1}}},
            {"name": "flow", "tool": "flow", "inputs": ["dpd"], "params": {"window": {"from": t_eq}, "slip": {}}}],
        "report": {
            "title": "C2" + (" smoke" if smoke else "") + ": slip length of the friction-shell wall",
            "scalars": [{"stage": "flow", "names": ["slip_length", "shear_gradient", "v_top", "shear_rate_apparent"],
                         "caption": "slip length b (r_c), velocity gradient G (1/tau), v_top (r_c/tau) and the apparent shear rate v_top/8 (1/tau)"}],
            "plots": [
                {"name": "slip_vs_gamma", "stage": "flow", "scalar": "slip_length", "x": "gamma_ls0", "series": "f",
                 "xlabel": "gamma_ls0", "ylabel": "b / r_c", "title": "Slip length against the wall's surface friction",
                 "theory": [{"kind": "constant", "value": 0, "label": "stick (b = 0)"}]},
                {"name": "profiles", "stage": "flow", "table": "profile_z", "x": "z", "y": ["v_x"], "xlabel": "z / r_c",
                 "ylabel": "v_x / (r_c/tau)", "title": "Velocity profiles"},
                {"name": "density", "stage": "flow", "table": "profile_z", "x": "z", "y": ["density"], "xlabel": "z / r_c",
                 "ylabel": "rho / r_c^-3", "title": "Density profiles"}]}}
    if not smoke:
        m["report"]["plots"].insert(1, {"name": "slip_vs_force", "stage": "flow", "scalar": "slip_length", "x": "f", "series": "gamma_ls0",
                                        "log": "x", "xlabel": "f (drive per particle; the apparent shear rate is in the scalars)",
                                        "ylabel": "b / r_c", "title": "Slip length against the drive"})
    return m


def fixed_sphere_manifest(smoke):
    gammas = [10 / 3] if smoke else [0, 10 / 3, 20 / 3]
    t_eq, t_avg = (100, 100) if smoke else (1000, 10000)
    force = 0.002 if smoke else 0.0011
    return {
        "study": "dpd_flow_fixed_sphere" + ("-smoke" if smoke else ""),
        "description": ("C3 smoke: " if smoke else "Study C3 (spec 60, spec 30 §8; Liu & Widmer-Cooper SI): ")
        + "a d = 2 sphere held fixed at the centre of an L_box = 8 box of DPD liquid (rho = 3, a = 25, gamma = 100, dt = 0.005; "
          "N_liquid = round(3 (512 - 4 pi/3)) placed uniformly outside the sphere; Mie(50,49) core, friction shell delta = 0.5 with "
          f"surface friction gamma_ls0, vector3d noise), a force f = {force} x on every liquid particle ("
        + ("the smoke drives twice as hard as the study, for signal; " if smoke else "")
        + "Decision: the smoke's mean flow, 0.073 at f = 0.002 and gamma_ls0 = 10/3, scaled to the apparent shear rate v/4 = 0.01 that "
          "spec 30 §8 asks for gives f = 0.0011; the measured v_x_mean/4 is reported); "
          f"{t_eq} tau to steady state, then {t_avg} tau averaged; the radial density rho(r) around the sphere and v_x in its mid-plane "
          "slab |x - x_c| < 0.25, both in bins of 0.1; jackknife errors over 10 blocks of the window.",
        "replicas": 1,
        "grid": {"gamma_ls0": gammas},
        "stages": [
            {"name": "config", "tool": "config", "replicate": False, "params": {
                "seed": 61, "placement": "colloids_in_liquid",
                "species": [{"name": "sphere", "shape": {"type": "sphere", "diameter": 2.0}}, LIQ],
                "composition": [{"species": "sphere", "count": 1}],
                "liquid": {"species": "liquid", "density": 3}, "box": {"edges": [8, 8, 8]}}},
            {"name": "dpd", "tool": "dpd", "inputs": ["config"], "params": {
                "seed": 62, "time_step": 0.005, "time": t_eq + t_avg, "observe_every": 1000,
                "liquid": {"a": 25, "gamma": 100},
                "colloids": {"species": ["sphere"], "gamma_surface": "${grid.gamma_ls0}", "fixed": True},
                "drive": {"force": [force, 0, 0]}, "profiles": {"z_bin": 0.1, "radial_bin": 0.1, "radial_max": 4}}},
            {"name": "flow", "tool": "flow", "inputs": ["dpd"], "params": {"window": {"from": t_eq}}}],
        "report": {
            "title": "C3" + (" smoke" if smoke else "") + ": liquid around a sphere held in a flow",
            "scalars": [{"stage": "flow", "names": ["v_x_mean"], "caption": "mean liquid velocity (r_c/tau); the apparent shear rate is v_x_mean/4"}],
            "plots": [
                {"name": "density_r", "stage": "flow", "table": "profile_r", "x": "r", "y": ["density"], "xlabel": "r / r_c",
                 "ylabel": "rho(r) / r_c^-3", "title": "Liquid density around the fixed sphere",
                 "theory": [{"kind": "constant", "value": 3, "label": "bulk density 3"}]},
                {"name": "velocity_r", "stage": "flow", "table": "profile_r", "x": "r", "y": ["v_x"], "xlabel": "r / r_c",
                 "ylabel": "v_x / (r_c/tau) in the mid-plane", "title": "Flow velocity around the fixed sphere (mid-plane slab)"}]}}


for name, m in (("dpd_slip_length-smoke", couette_manifest(True)), ("dpd_slip_length", couette_manifest(False)),
                ("dpd_flow_fixed_sphere-smoke", fixed_sphere_manifest(True)), ("dpd_flow_fixed_sphere", fixed_sphere_manifest(False))):
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(m, f, indent=2)
        f.write("\n")


# A validation variant of C2 (docs/validation.md): the sign change of b, resolved at one drive.
def couette_validation():
    m = couette_manifest(False)
    m["study"] = "validation_dpd_slip_length_f0.05"
    m["grid"] = {"gamma_ls0": [0, 1, 2, 10 / 3, 5, 20 / 3, 10, 30], "f": [0.05]}
    m["stages"][1]["params"]["time"] = 2000
    m["stages"][2]["params"]["window"] = {"from": 200}
    m["description"] = ("C2 at one drive, f = 0.05, for the sign change of the slip length: gamma_ls0 in {0, 1, 2, 10/3, 5, 20/3, 10, 30}, "
                        "2000 tau per point, the last 1800 tau averaged. " + m["description"].split(": ", 1)[1])
    m["report"]["plots"] = [p for p in m["report"]["plots"] if p["name"] != "slip_vs_force"]
    return m


with open(os.path.join(OUT, "validation", "dpd_slip_length_f0.05.json"), "w") as f:
    json.dump(couette_validation(), f, indent=2)
    f.write("\n")


# --- C0: liquid checks (spec 60 C0) ----------------------------------------------------------------
def liquid_checks():
    return {
        "study": "dpd_liquid_checks",
        "description": "Study C0 (spec 60): checks of the pure DPD liquid, rho = 3, a = 25, L_box = 8 (1536 particles placed uniformly, "
                       "relaxed 20 tau at gamma = 4.5, discarded). (1) Thermostatted, gamma in {4.5, 100}, dt = 0.005, 2e4 steps: the kinetic "
                       "temperature (target 1; at gamma = 100 the velocity-Verlet scheme runs about 0.5% hot, spec 30 §2) and the pressure "
                       "(Groot-Warren rho + 0.101 a rho^2 = 25.7) over the last 1.8e4 steps, errors from 10 blocks; g(r) from frames every "
                       "100 steps. (2) Thermostat off (gamma = 0: conservative forces only), dt in {0.0025, 0.005, 0.01}, 1e4 steps from the "
                       "relaxed state: the drift of the total energy per particle (slope against time, and its change over the run), which "
                       "for velocity Verlet scales as dt^2. Itself its smoke (about a minute on 2 cores).",
        "replicas": 1,
        "grid": {"gamma": [4.5, 100], "dt": [0.0025, 0.005, 0.01]},
        "stages": [
            {"name": "config", "tool": "config", "params": {
                "seed": 71, "placement": "uniform", "species": [LIQ], "composition": [{"species": "liquid", "count": 1536}],
                "box": {"edges": [8, 8, 8]}}},
            {"name": "relax", "tool": "dpd", "inputs": ["config"], "params": {
                "seed": 72, "time_step": 0.005, "time": 20, "observe_every": 1000, "liquid": {"a": 25, "gamma": 4.5}}},
            {"name": "thermostatted", "tool": "dpd", "inputs": ["relax"], "params": {
                "seed": 73, "time_step": 0.005, "steps": 20000, "observe_every": 100, "velocities": "input",
                "liquid": {"a": 25, "gamma": "${grid.gamma}"}, "frames": {"every_steps": 100}}},
            {"name": "nve", "tool": "dpd", "inputs": ["relax"], "params": {
                "seed": 74, "time_step": "${grid.dt}", "steps": 10000, "observe_every": 100, "velocities": "input",
                "liquid": {"a": 25, "gamma": 0}}},
            {"name": "temperature", "tool": "observables", "inputs": ["thermostatted"], "params": {
                "means": ["kinetic_temperature", "pressure", "potential_energy"], "window": {"from": 10}}},
            {"name": "gr", "tool": "structure", "inputs": ["thermostatted"], "params": {"dr": 0.02, "r_max": 3, "window": {"from": 10}}},
            {"name": "drift", "tool": "observables", "inputs": ["nve"], "params": {"drifts": ["total_energy"]}}],
        "report": {
            "title": "C0: checks of the DPD liquid",
            "scalars": [
                {"stage": "temperature", "names": ["kinetic_temperature", "pressure", "potential_energy"],
                 "caption": "kinetic temperature (kT; target 1), pressure (kT/r_c^3; Groot-Warren 25.7) and potential energy per particle (kT)"},
                {"stage": "drift", "names": ["total_energy_drift", "total_energy_change"],
                 "caption": "thermostat off: drift of the total energy per particle (kT/tau) and its change over the 1e4 steps (kT)"}],
            "plots": [
                {"name": "gr", "stage": "gr", "table": "structure_liquid_liquid", "x": "r", "y": ["g"], "xlabel": "r / r_c",
                 "ylabel": "g(r)", "title": "Radial distribution function of the liquid"},
                {"name": "drift_vs_dt", "stage": "drift", "scalar": "total_energy_change", "x": "dt", "log": "xy",
                 "xlabel": "dt / tau", "ylabel": "energy change per particle over 1e4 steps / kT", "title": "Energy drift without thermostat",
                 "theory": [{"kind": "power", "prefactor": 1.0, "exponent": 2, "label": "dt^2 (the second-order slope, for comparison)"}]}]}}


def liquid_checks_smoke():
    """Spec 60: C0's smoke is the study itself (about a minute): the same runs under the smoke's name."""
    m = liquid_checks()
    m["study"] += "-smoke"
    m["description"] = "C0 smoke, the study itself (spec 60): " + m["description"]
    m["report"]["title"] = "C0 smoke: checks of the DPD liquid"
    return m


for name, m in (("dpd_liquid_checks", liquid_checks()), ("dpd_liquid_checks-smoke", liquid_checks_smoke())):
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(m, f, indent=2)
        f.write("\n")
