#pragma once
// Closed-form infinite-dilution hydrodynamics: an independent reference for testing the hydro code
// (spec 70-theory.md §6.2 and §7.3, spec 40-lb-raspberry.md §8.6).
//
// Units: every function takes the shear viscosity η (`eta`) and, where a diffusivity is returned,
// the thermal energy k_BT (`kT`) as arguments with default 1; lengths are in whatever unit the
// semi-axes / radii / lengths are given in. Frictions are F/v (translation) and T/ω (rotation).
//
//   Sphere           : Stokes (1851) ξ_t = 6πηR, Kirchhoff/Lamb ξ_r = 8πηR³; Stokes–Einstein
//                      D_t = k_BT/(6πηR), Stokes–Einstein–Debye D_r = k_BT/(8πηR³).
//   Triaxial ellipsoid: Jeffery, Proc. R. Soc. A 102, 161 (1922) and Perrin, J. Phys. Radium 5,
//                      497 (1934) (also Happel & Brenner, "Low Reynolds number hydrodynamics",
//                      §5-11). Semi-axes (b1, b2, b3) along the body x, y, z axes;
//                        Δ(s) = √((b1²+s)(b2²+s)(b3²+s)),  χ = ∫₀^∞ ds/Δ,
//                        P_i  = ∫₀^∞ ds/((b_i²+s)Δ),
//                        ξ_i^t = 16πη/(χ + b_i² P_i),
//                        ξ_i^r = 16πη(b_j² + b_k²)/[3(b_j² P_j + b_k² P_k)]   ({i,j,k} = {1,2,3}).
//   Cylinder         : Tirado, López Martínez & García de la Torre, J. Chem. Phys. 81, 2047 (1984),
//                      length L, diameter d, p = L/d (fits valid for 2 ≲ p ≲ 30).
//   Capacitance      : (units where a sphere's C is its radius) of a triaxial ellipsoid C = 2/χ
//                      (Kellogg, "Foundations of potential theory" (1929) §VII.6; Landau & Lifshitz,
//                      "Electrodynamics of continuous media" §4); closed forms for spheroids with
//                      polar semi-axis a and equatorial c: prolate (a > c) C = √(a²−c²)/arccosh(a/c),
//                      oblate (a < c) C = √(c²−a²)/arccos(a/c) (Smythe, "Static and dynamic
//                      electricity" §5.03). For every ellipsoid the orientational mean translational
//                      mobility is χ/(12πη), i.e. R_h = 1/(6πη D̄_t) = C exactly (Hubbard & Douglas,
//                      Phys. Rev. E 47, R2983 (1993)); for other convex bodies R_h ≥ C (Blawzdziewicz,
//                      Wajnryb, Given & Hubbard, Phys. Fluids 17, 033602 (2005)).
//
// Quadrature: the integrals are evaluated in y = ln s (ds = e^y dy), where the integrands are
// smooth bumps located near y = ln b_i². The real line is split at y_lo = ln(min b²) − 40 and
// y_hi = ln(max b²) + 40: [y_lo, y_hi] goes to gsl_integration_qagp with the break points ln b_i²,
// the two tails to gsl_integration_qagil / qagiu. The integrand is formed in log space, so it never
// overflows. Requested relative accuracy 1e-11 (the result is good to ≲ 1e-10 relative).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace anisodyn::theory {

inline constexpr double kPi = std::numbers::pi;

// ---- sphere --------------------------------------------------------------------------------------

inline double sphere_translational_friction(double R, double eta = 1.0) { return 6.0 * kPi * eta * R; }
inline double sphere_rotational_friction(double R, double eta = 1.0) {
  return 8.0 * kPi * eta * R * R * R;
}
// Stokes–Einstein D_t = k_BT/(6πηR).
inline double stokes_einstein_diffusion(double R, double eta = 1.0, double kT = 1.0) {
  return kT / sphere_translational_friction(R, eta);
}
// Stokes–Einstein–Debye D_r = k_BT/(8πηR³).
inline double stokes_einstein_debye_rotational_diffusion(double R, double eta = 1.0, double kT = 1.0) {
  return kT / sphere_rotational_friction(R, eta);
}

// ---- triaxial ellipsoid (Jeffery 1922, Perrin 1934) ---------------------------------------------

struct EllipsoidIntegrals {
  double chi;                // χ = ∫₀^∞ ds/Δ(s)
  std::array<double, 3> P;   // P_i = ∫₀^∞ ds/((b_i²+s)Δ(s))
};

namespace detail {

struct EllipsoidIntegrand {
  std::array<double, 3> log_b2;  // ln b_i²
  int extra;                     // −1: χ; 0..2: P_i (extra factor 1/(b_i²+s))
};

// ln(b² + e^y) from ln b² and y, without overflow.
inline double log_add_exp(double u, double v) {
  const double m = std::max(u, v);
  return m + std::log1p(std::exp(-std::abs(u - v)));
}

// s/Δ(s) or s/((b_i²+s)Δ(s)) with s = e^y (the Jacobian ds = s dy included).
inline double ellipsoid_integrand(double y, void* params) {
  const auto& p = *static_cast<const EllipsoidIntegrand*>(params);
  const std::array<double, 3> L = {log_add_exp(p.log_b2[0], y), log_add_exp(p.log_b2[1], y),
                                   log_add_exp(p.log_b2[2], y)};
  double log_f = y - 0.5 * (L[0] + L[1] + L[2]);
  if (p.extra >= 0) log_f -= L[static_cast<std::size_t>(p.extra)];
  return std::exp(log_f);
}

struct WorkspaceDeleter {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};

// Restores the previous GSL error handler on scope exit; failures are reported by status instead.
struct GslHandlerOff {
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  GslHandlerOff() = default;
  GslHandlerOff(const GslHandlerOff&) = delete;
  GslHandlerOff& operator=(const GslHandlerOff&) = delete;
  ~GslHandlerOff() { gsl_set_error_handler(old); }
};

inline void check_gsl(int status, const char* what) {
  if (status != GSL_SUCCESS)
    throw std::runtime_error(std::string("hydro_theory: ") + what + ": " + gsl_strerror(status));
}

inline double integrate_ellipsoid(const std::array<double, 3>& b, int extra) {
  constexpr std::size_t kLimit = 2000;
  constexpr double kEpsRel = 1e-11;
  constexpr double kMargin = 40.0;  // in y = ln s; tails beyond it are still integrated (qagil/qagiu)
  EllipsoidIntegrand params{{2.0 * std::log(b[0]), 2.0 * std::log(b[1]), 2.0 * std::log(b[2])}, extra};
  gsl_function f{&ellipsoid_integrand, &params};

  std::vector<double> pts{params.log_b2.begin(), params.log_b2.end()};
  std::sort(pts.begin(), pts.end());
  const double y_lo = pts.front() - kMargin;
  const double y_hi = pts.back() + kMargin;
  std::vector<double> breaks{y_lo};
  for (double y : pts)
    if (y > breaks.back() + 1e-12) breaks.push_back(y);
  breaks.push_back(y_hi);

  GslHandlerOff guard;
  std::unique_ptr<gsl_integration_workspace, WorkspaceDeleter> w(gsl_integration_workspace_alloc(kLimit));
  if (!w) throw std::runtime_error("hydro_theory: gsl_integration_workspace_alloc failed");
  double mid = 0, lo = 0, hi = 0, err = 0;
  check_gsl(gsl_integration_qagp(&f, breaks.data(), breaks.size(), 0.0, kEpsRel, kLimit, w.get(), &mid, &err),
            "qagp");
  // The tails are ≲ e^{-20} of the total; an absolute target relative to `mid` suffices.
  check_gsl(gsl_integration_qagil(&f, y_lo, mid * 1e-14, kEpsRel, kLimit, w.get(), &lo, &err), "qagil");
  check_gsl(gsl_integration_qagiu(&f, y_hi, mid * 1e-14, kEpsRel, kLimit, w.get(), &hi, &err), "qagiu");
  return lo + mid + hi;
}

inline void check_semi_axes(double b1, double b2, double b3) {
  if (!(b1 > 0 && b2 > 0 && b3 > 0 && std::isfinite(b1) && std::isfinite(b2) && std::isfinite(b3)))
    throw std::invalid_argument("hydro_theory: ellipsoid semi-axes must be positive and finite");
}

}  // namespace detail

// χ and P_1..P_3 for semi-axes (b1, b2, b3). Sphere: χ = 2/R, P_i = 2/(3R³).
inline EllipsoidIntegrals ellipsoid_integrals(double b1, double b2, double b3) {
  detail::check_semi_axes(b1, b2, b3);
  const std::array<double, 3> b{b1, b2, b3};
  return {detail::integrate_ellipsoid(b, -1),
          {detail::integrate_ellipsoid(b, 0), detail::integrate_ellipsoid(b, 1),
           detail::integrate_ellipsoid(b, 2)}};
}

// ξ_i^t = 16πη/(χ + b_i² P_i) for translation along body axis i (Perrin 1934).
inline std::array<double, 3> ellipsoid_translational_friction(double b1, double b2, double b3,
                                                              double eta = 1.0) {
  const EllipsoidIntegrals I = ellipsoid_integrals(b1, b2, b3);
  const std::array<double, 3> b2s{b1 * b1, b2 * b2, b3 * b3};
  std::array<double, 3> xi{};
  for (std::size_t i = 0; i < 3; ++i) xi[i] = 16.0 * kPi * eta / (I.chi + b2s[i] * I.P[i]);
  return xi;
}

// ξ_i^r = 16πη(b_j² + b_k²)/[3(b_j² P_j + b_k² P_k)] for rotation about body axis i
// (Jeffery 1922 torque on an ellipsoid; Perrin 1934).
inline std::array<double, 3> ellipsoid_rotational_friction(double b1, double b2, double b3,
                                                           double eta = 1.0) {
  const EllipsoidIntegrals I = ellipsoid_integrals(b1, b2, b3);
  const std::array<double, 3> b2s{b1 * b1, b2 * b2, b3 * b3};
  std::array<double, 3> xi{};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3, k = (i + 2) % 3;
    xi[i] = 16.0 * kPi * eta * (b2s[j] + b2s[k]) / (3.0 * (b2s[j] * I.P[j] + b2s[k] * I.P[k]));
  }
  return xi;
}

struct EllipsoidDiffusion {
  std::array<double, 3> D_trans;  // k_BT/ξ_i^t, body axes x, y, z
  std::array<double, 3> D_rot;    // k_BT/ξ_i^r, about body axes x, y, z
};

// Body-frame diffusion coefficients; k_BT = η = 1 unless given.
inline EllipsoidDiffusion ellipsoid_diffusion(double b1, double b2, double b3, double eta = 1.0,
                                              double kT = 1.0) {
  const auto xt = ellipsoid_translational_friction(b1, b2, b3, eta);
  const auto xr = ellipsoid_rotational_friction(b1, b2, b3, eta);
  EllipsoidDiffusion d{};
  for (std::size_t i = 0; i < 3; ++i) {
    d.D_trans[i] = kT / xt[i];
    d.D_rot[i] = kT / xr[i];
  }
  return d;
}

// ---- capacitance (electrostatics; a sphere's C is its radius) -----------------------------------

// C = 2/χ for semi-axes (b1, b2, b3).
inline double ellipsoid_capacitance(double b1, double b2, double b3) {
  return 2.0 / ellipsoid_integrals(b1, b2, b3).chi;
}

// Spheroid with polar semi-axis a and equatorial semi-axes c (closed forms, no quadrature).
inline double spheroid_capacitance(double a, double c) {
  detail::check_semi_axes(a, c, c);
  if (a > c) return std::sqrt(a * a - c * c) / std::acosh(a / c);
  if (a < c) return std::sqrt(c * c - a * a) / std::acos(a / c);
  return a;
}

// ---- cylinder (Tirado, López Martínez & García de la Torre, J. Chem. Phys. 81, 2047 (1984)) ----

struct CylinderDiffusion {
  double D_par;   // translation along the axis
  double D_perp;  // translation perpendicular to the axis
  double D_t;     // orientationally averaged translation (TGdlT's own fit, not (D_par + 2D_perp)/3)
  double D_r;     // end-over-end rotation
};

// Length L, diameter d, p = L/d; k_BT = η = 1 unless given.
//   D_par  = k_BT(ln p + ν_par)/(2πηL),   ν_par  = −0.207 + 0.980/p − 0.133/p²
//   D_perp = k_BT(ln p + ν_perp)/(4πηL),  ν_perp =  0.839 + 0.185/p + 0.233/p²
//   D_t    = k_BT(ln p + ν_t)/(3πηL),     ν_t    =  0.312 + 0.565/p − 0.100/p²
//   D_r    = 3k_BT(ln p + ν_r)/(πηL³),    ν_r    = −0.662 + 0.917/p − 0.050/p²
inline CylinderDiffusion tirado_cylinder_diffusion(double L, double d, double eta = 1.0, double kT = 1.0) {
  if (!(L > 0 && d > 0)) throw std::invalid_argument("hydro_theory: cylinder L and d must be positive");
  const double p = L / d, lp = std::log(p), ip = 1.0 / p, ip2 = ip * ip;
  const double nu_par = -0.207 + 0.980 * ip - 0.133 * ip2;
  const double nu_perp = 0.839 + 0.185 * ip + 0.233 * ip2;
  const double nu_t = 0.312 + 0.565 * ip - 0.100 * ip2;
  const double nu_r = -0.662 + 0.917 * ip - 0.050 * ip2;
  return {kT * (lp + nu_par) / (2.0 * kPi * eta * L), kT * (lp + nu_perp) / (4.0 * kPi * eta * L),
          kT * (lp + nu_t) / (3.0 * kPi * eta * L), 3.0 * kT * (lp + nu_r) / (kPi * eta * L * L * L)};
}

}  // namespace anisodyn::theory
