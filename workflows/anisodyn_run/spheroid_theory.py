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
