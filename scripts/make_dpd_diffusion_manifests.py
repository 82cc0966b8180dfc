#!/usr/bin/env python3
"""Writes the C4 and C5 manifests (spec 60: dpd_sphere_diffusion, dpd_rod_diffusion and their
smokes) from Table S1 and the Tirado-Garcia de la Torre equivalent diameters (spec 30 §10), so that
the per-system x and y scales of the reduced plots follow from the formulas, not by hand.
Run from anywhere: scripts/make_dpd_diffusion_manifests.py"""
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
    series_t, series_r = [], []
    for d, L in rods:
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
            "scalars": [{"stage": "msd", "names": ["D_tot_rod", "D_par_rod", "D_perp_rod", "D_body_z_rod", "D_body_x_rod"],
                         "caption": "D_t, D_par, D_perp (lab frame, to the axis at the time origin) and the body-frame D_par (body_z), D_perp (body_x), r_c^2/tau"},
                        {"stage": "rotation", "names": ["Dr_msad_L_rod", "Dr_C1_L_rod"], "caption": "D_r of the rod axis from the MSAD (4 D_r t) and from C1, 1/tau"}],
            "plots": [
                {"name": "reduced_D_t", "x": "L_box", "x_power": -1, "series": series_t,
                 "theory": [{"kind": "hasimoto", "boundary": "stick", "band": 0.2}],
                 "xlabel": "phi_t^(1/3)", "ylabel": f"D~_t = D_t eta d_t (eta = {ETA})", "title": "Reduced translational diffusion of the rod"},
                {"name": "reduced_D_r", "x": "L_box", "x_power": -1, "series": series_r,
                 "theory": [{"kind": "periodic_rotation", "band": 0.2}],
                 "xlabel": "phi_r^(1/3)", "ylabel": f"D~_r = D_r eta d_r^3 (eta = {ETA})", "title": "Reduced rotational diffusion of the rod"}]}}
    if zip_:
        m["zip"] = zip_
    return m


for name, m in (("dpd_sphere_diffusion-smoke", sphere_manifest(True)), ("dpd_sphere_diffusion", sphere_manifest(False)),
                ("dpd_rod_diffusion-smoke", rod_manifest(True)), ("dpd_rod_diffusion", rod_manifest(False))):
    with open(os.path.join(OUT, f"{name}.json"), "w") as f:
        json.dump(m, f, indent=2)
        f.write("\n")
