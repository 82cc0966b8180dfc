"""Hydrodynamic factors of a spheroid, spec 40 §8.6 (tabulated in spec 70 §7.3).

A spheroid has semi-axis a along its symmetry axis and c = b across; phi = a/c (phi < 1 oblate, > 1
prolate). The factors compare effective radii with a (lab frame, Perrin) or c (body frame):
  A = a / R_eff,t   and   B = (a / R_eff,r)^3            (orientation averages, lab frame)
  t_ax, t_perp = R_eff,t along / across the axis, over c  (Happel-Brenner E, F prolate; G, H oblate)
  r_ax, r_perp = (R_eff,r about / across the axis, over c)^3   (Perrin I, J prolate; K, L oblate)
  t_ratio = t_perp / t_ax = D_t,ax / D_t,perp and r_ratio = r_perp / r_ax = D_r,ax / D_r,perp: the
  body-frame anisotropies, which need no calibration of the effective radius (frictions scale alike)
The rotational radii come from Perrin's integrals P, Q, evaluated with s = e^y and Gauss-Legendre
quadrature; the translational ones from the closed forms E-H (and, as a check, from the integrals
chi and P_i of the general ellipsoid). Lengths are free: the factors depend on phi alone."""
import math

import numpy as np

# Gauss-Legendre in y = ln s over [-60, 60]: the integrands fall off as s^(-5/2) … s^(-3/2) at large s
# and are flat at small s; 400 nodes give relative accuracy far below 1e-8 for 1/10 <= phi <= 10.
_Y_RANGE = 60.0
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(400)


def _integral(f):
    """∫_0^∞ f(s) ds with s = e^y."""
    y = _Y_RANGE * _NODES
    s = np.exp(y)
    return float(_Y_RANGE * np.sum(_WEIGHTS * f(s) * s))


def perrin_P(a, c):
    """P = ∫ ds / [(c² + s)(a² + s)^(3/2)]."""
    return _integral(lambda s: 1.0 / ((c * c + s) * (a * a + s) ** 1.5))


def perrin_Q(a, c):
    """Q = ∫ ds / [(c² + s)² (a² + s)^(1/2)]."""
    return _integral(lambda s: 1.0 / ((c * c + s) ** 2 * (a * a + s) ** 0.5))


def lab_factors(phi):
    """(A, B) of spec 40 §8.6: Perrin's orientation-averaged translational and rotational factors."""
    if phi == 1.0:
        return 1.0, 1.0
    p2 = phi ** -2
    if phi < 1.0:
        A = math.atan(math.sqrt(p2 - 1.0)) / math.sqrt(abs(1.0 - p2))
    else:
        A = math.log(phi + math.sqrt(phi * phi - 1.0)) / math.sqrt(abs(1.0 - p2))
    B = (1.0 + 3.0 * p2 * A) / (2.0 * p2 * (1.0 + p2))
    return A, B


def translation_factors(phi):
    """(t_ax, t_perp): E, F (prolate) or G, H (oblate) of spec 40 §8.6; 1, 1 for a sphere."""
    if phi == 1.0:
        return 1.0, 1.0
    if phi > 1.0:
        d = phi * phi - 1.0
        E = (8.0 / 3.0) / (-2.0 * phi / d + (2.0 * phi * phi - 1.0) / d ** 1.5 * math.log((phi + math.sqrt(d)) / (phi - math.sqrt(d))))
        F = (8.0 / 3.0) / (phi / d + (2.0 * phi * phi - 3.0) / d ** 1.5 * math.log(phi + math.sqrt(d)))
        return E, F
    d = 1.0 - phi * phi
    G = (8.0 / 3.0) / (2.0 * phi / d + (2.0 - 4.0 * phi * phi) / d ** 1.5 * math.atan(math.sqrt(d) / phi))
    H = (8.0 / 3.0) / (-phi / d + (3.0 - 2.0 * phi * phi) / d ** 1.5 * math.asin(math.sqrt(d)))
    return G, H


def rotation_factors(phi):
    """(r_ax, r_perp): I, J (prolate) or K, L (oblate): (R_eff,r / c)^3 about and across the axis,
    R_eff,x,r = (2/(3Q))^(1/3), R_eff,yz,r = (2(a² + c²)/(3(a²P + c²Q)))^(1/3), with c = 1."""
    a, c = phi, 1.0
    P, Q = perrin_P(a, c), perrin_Q(a, c)
    return 2.0 / (3.0 * Q), 2.0 * (a * a + c * c) / (3.0 * (a * a * P + c * c * Q))


def axis_translation_radii(phi):
    """(R_ax, R_perp) / c from the general ellipsoid's integrals: xi_i = 16 pi eta / (chi + b_i² P_i),
    R_i = xi_i / (6 pi eta) = 8 / (3 (chi + b_i² P_i)) (the cross-check of E-H)."""
    axes = (phi, 1.0, 1.0)

    def delta(s):
        return np.sqrt((axes[0] ** 2 + s) * (axes[1] ** 2 + s) * (axes[2] ** 2 + s))

    chi = _integral(lambda s: 1.0 / delta(s))
    radii = []
    for b in (axes[0], axes[1]):
        P = _integral(lambda s, b=b: 1.0 / ((b * b + s) * delta(s)))
        radii.append(8.0 / (3.0 * (chi + b * b * P)))
    return tuple(radii)


def factor(name, phi):
    """One factor by name: A, B, t_ax, t_perp, r_ax, r_perp, t_ratio, r_ratio."""
    if name in ("A", "B"):
        return lab_factors(phi)["AB".index(name)]
    if name in ("t_ax", "t_perp"):
        return translation_factors(phi)[0 if name == "t_ax" else 1]
    if name in ("r_ax", "r_perp"):
        return rotation_factors(phi)[0 if name == "r_ax" else 1]
    if name == "t_ratio":
        t_ax, t_perp = translation_factors(phi)
        return t_perp / t_ax
    if name == "r_ratio":
        r_ax, r_perp = rotation_factors(phi)
        return r_perp / r_ax
    raise ValueError(f"unknown spheroid factor '{name}' (A, B, t_ax, t_perp, r_ax, r_perp, t_ratio, r_ratio)")


FACTORS = ("A", "B", "t_ax", "t_perp", "r_ax", "r_perp", "t_ratio", "r_ratio")


# --- spec 70 §7.3's printed table and verified identities (checks: study D0, tests) ----------------
SPEC70_COLUMNS = ("A", "B", "t_ax", "t_perp", "r_ax", "r_perp", "R_eff_t")
SPEC70_TABLE = """1/10 0.1478 0.0022 0.8525 0.6133 0.4789 0.4305 6.195
1/5 0.2795 0.0169 0.8615 0.6596 0.5344 0.4480 5.200
1/4 0.3403 0.0319 0.8673 0.6823 0.5624 0.4608 4.956
1/3 0.4352 0.0708 0.8787 0.7197 0.6095 0.4882 4.695
1/2 0.6046 0.2064 0.9053 0.7927 0.7050 0.5658 4.428
2/3 0.7523 0.4156 0.9352 0.8636 0.8021 0.6754 4.311
4/5 0.8580 0.6271 0.9606 0.9189 0.8807 0.7877 4.269
9/10 0.9313 0.8064 0.9801 0.9597 0.9402 0.8870 4.254
10/9 1.0717 1.2292 1.0223 1.0441 1.0669 1.1423 4.254
5/4 1.1552 1.5330 1.0505 1.0985 1.1510 1.3460 4.269
3/2 1.2912 2.1197 1.1017 1.1942 1.3037 1.7902 4.313
2 1.5207 3.4248 1.2039 1.3789 1.6134 3.0099 4.436
3 1.8697 6.5741 1.4045 1.7276 2.2439 7.0223 4.728
4 2.1311 10.538 1.5979 2.0565 2.8842 13.583 5.025
5 2.3397 15.394 1.7848 2.3710 3.5304 23.203 5.311
10 3.0083 53.973 2.6471 3.8115 6.8047 133.68 6.557"""


def half_unit(printed):
    """Half a unit of the last printed digit."""
    digits = len(printed.split(".")[1]) if "." in printed else 0
    return 0.5 * 10.0 ** -digits


def table_comparison():
    """(phi as printed, column, computed, printed text, |computed - printed|, half a unit of its last digit) for every
    entry of spec 70 §7.3's factor table; R_eff_t = a/A with a = 4.25 phi^(2/3) (constant volume)."""
    out = []
    for line in SPEC70_TABLE.splitlines():
        words = line.split()
        num, _, den = words[0].partition("/")
        phi = float(num) / float(den or 1)
        values = [factor(name, phi) for name in SPEC70_COLUMNS[:-1]] + [4.25 * phi ** (2.0 / 3.0) / lab_factors(phi)[0]]
        for name, value, printed in zip(SPEC70_COLUMNS, values, words[1:]):
            out.append((words[0], name, value, printed, abs(value - float(printed)), half_unit(printed)))
    return out


def identity_checks():
    """(what, computed, reference) for spec 70 §7.3's verified identities: E-H against the ellipsoid integrals,
    the harmonic and rotational means, the sphere and the disk limits, (I/J)^(1/3) at 10/9 and 10."""
    out = []
    for phi in (0.1, 0.25, 0.5, 0.9, 10 / 9, 2.0, 5.0, 10.0):
        t_ax, t_perp = translation_factors(phi)
        i_ax, i_perp = axis_translation_radii(phi)
        A, B = lab_factors(phi)
        r_ax, r_perp = rotation_factors(phi)
        out += [(f"phi = {phi:.4g}: E/G from the ellipsoid integrals", t_ax, i_ax),
                (f"phi = {phi:.4g}: F/H from the ellipsoid integrals", t_perp, i_perp),
                (f"phi = {phi:.4g}: harmonic mean 3/(1/(c t_ax) + 2/(c t_perp)) = a/A", 3.0 / (1.0 / t_ax + 2.0 / t_perp), phi / A),
                (f"phi = {phi:.4g}: rotational mean a^3/[3/(1/r_ax + 2/r_perp)] = B", phi ** 3 / (3.0 / (1.0 / r_ax + 2.0 / r_perp)), B)]
    G, H = translation_factors(1e-6)
    out += [("disk limit G(phi -> 0) = 8/(3 pi)", G, 8.0 / (3.0 * math.pi)), ("disk limit H(phi -> 0) = 16/(9 pi)", H, 16.0 / (9.0 * math.pi))]
    out += [(f"sphere: {name}(1) = 1", factor(name, 1.0), 1.0) for name in ("A", "B", "t_ax", "t_perp", "r_ax", "r_perp")]
    out += [(f"(I/J)^(1/3) at phi = {label} (printed {printed})", (rotation_factors(p)[0] / rotation_factors(p)[1]) ** (1 / 3), printed)
            for label, p, printed in (("10/9", 10 / 9, 0.977), ("10", 10.0, 0.370))]
    return out
