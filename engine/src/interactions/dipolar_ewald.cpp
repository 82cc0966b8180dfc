// Dipolar Ewald summation (spec 10 §6.2). Formulas, parameter choice and measured accuracy and
// cost: docs/ewald.md.
#include "anisodyn/interactions/dipolar_ewald.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "anisodyn/core/error.hpp"
#include "anisodyn/interactions/dipolar_pair.hpp"

namespace anisodyn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr long double kPiL = 3.141592653589793238462643383279502884L;
constexpr int kMaxNMax = 100;

std::string num(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

/// Fixed-order sum: 8 interleaved partial sums combined pairwise. The inner loop has no dependency
/// across lanes, so the compiler may vectorise it without changing a single bit, and the result
/// depends only on the values, not on the history of the object or on the vector width.
double lane_sum(const double* v, std::size_t n) {
  double acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  const std::size_t m = n - n % 8;
  for (std::size_t k = 0; k < m; k += 8)
    for (std::size_t l = 0; l < 8; ++l) acc[l] += v[k + l];
  for (std::size_t k = m; k < n; ++k) acc[k - m] += v[k];
  return ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]));
}

/// Smooth remainders of the real-space radial functions, in long double:
///   b(s) = B(r) − 1/r³ = −erf(κr)/r³ + (2κ/√π) e^{−κ²r²}/r²,
///   c(s) = C(r) − 3/r⁵ = −3 erf(κr)/r⁵ + (2κ/√π)(2κ² + 3/r²) e^{−κ²r²}/r²,
/// s = r². Both are entire functions of τ = κ²s; for τ < 1/2 their Taylor series avoid the
/// cancellation between the two terms:
///   b = κ³ (2/√π) Σ_{n≥1} (−1)ⁿ (2n/(2n+1)) τ^{n−1}/n!,
///   c = κ⁵ (2/√π) Σ_{n≥2} (−1)ⁿ (4n(1−n)/(2n+1)) τ^{n−2}/n!.
void exact_remainders(long double s, long double kappa, long double& b, long double& c) {
  const long double k2 = kappa * kappa, tau = k2 * s;
  const long double tsp = 2.0L / std::sqrt(kPiL);
  if (tau < 0.5L) {
    long double sb = 0, sc = 0;
    long double a = -1.0L;   // (−1)ⁿ τ^{n−1}/n! at n = 1
    long double a2 = 0.5L;   // (−1)ⁿ τ^{n−2}/n! at n = 2
    for (int n = 1; n < 40; ++n) {
      sb += a * (2.0L * n / (2.0L * n + 1.0L));
      a *= -tau / (n + 1);
    }
    for (int n = 2; n < 40; ++n) {
      sc += a2 * (4.0L * n * (1.0L - n) / (2.0L * n + 1.0L));
      a2 *= -tau / (n + 1);
    }
    b = kappa * k2 * tsp * sb;
    c = kappa * k2 * k2 * tsp * sc;
    return;
  }
  const long double r = std::sqrt(s), e = std::exp(-tau), ef = std::erf(kappa * r);
  b = -ef / (s * r) + tsp * kappa * e / s;
  c = -3.0L * ef / (s * s * r) + tsp * kappa * (2.0L * k2 + 3.0L / s) * e / s;
}

/// Exact ψ(d) = B − (Ê·d)² C in long double (constants only).
long double exact_psi(const Vec3& d, const Vec3& e, long double kappa) {
  const long double s = static_cast<long double>(d.squaredNorm());
  const long double r = std::sqrt(s), x = kappa * r;
  const long double tsp = 2.0L / std::sqrt(kPiL);
  const long double ex = std::exp(-x * x), ec = std::erfc(x);
  const long double B = ec / (s * r) + tsp * kappa * ex / s;
  const long double C = 3.0L * ec / (s * s * r) + tsp * kappa * (2.0L * kappa * kappa + 3.0L / s) * ex / s;
  const long double ed = static_cast<long double>(e.dot(d));
  return B - ed * ed * C;
}

/// Everything the real-space pair function needs, as plain scalars (keeps the loops vectorisable).
struct RealSpaceKernel {
  double Lx, Ly, Lz, iLx, iLy, iLz;
  double ex, ey, ez;
  double rc2, alpha;             // x = s·alpha − 1 maps s ∈ [0, r_cut²] onto [−1, 1]
  const double* cb;              // monomial coefficients of b(s) in x
  const double* cc;              // and of c(s)
};

// Polynomial degrees compiled for the remainders (smallest adequate one is chosen at run time).
constexpr int kDegrees[] = {12, 14, 16, 18, 20, 22, 24, 26, 28, 32, 36, 40, 44, 48};
constexpr int kMaxDegree = 48;

/// ψ(d) for a separation d (minimum image applied here); 0 beyond r_cut.
/// kD = 0: bare dipolar term only (minimum_image_only mode); otherwise the degree of b, c.
/// No branches and no indexed loads, so a loop over j vectorises.
template <int kD>
inline double psi(const RealSpaceKernel& k, double dx, double dy, double dz) {
  dx -= k.Lx * std::nearbyint(dx * k.iLx);
  dy -= k.Ly * std::nearbyint(dy * k.iLy);
  dz -= k.Lz * std::nearbyint(dz * k.iLz);
  const double s = dx * dx + dy * dy + dz * dz;
  const double ed = k.ex * dx + k.ey * dy + k.ez * dz;
  const double ed2 = ed * ed;
  double v = bare_dipolar_psi(s, ed2);  // the one point-dipole pair function (dipolar_pair.hpp)
  if constexpr (kD > 0) {
    const double x = s * k.alpha - 1.0;
    double b = k.cb[kD], c = k.cc[kD];
#pragma GCC unroll 64
    for (int m = kD - 1; m >= 0; --m) {
      b = b * x + k.cb[m];
      c = c * x + k.cc[m];
    }
    v += b - ed2 * c;
  }
  return s < k.rc2 ? v : 0.0;
}

/// Real-space sum Σ_{j≠i} w_j [ψ(r_new − r_j) − ψ(r_old − r_j)] over all particles in index order.
template <int kD>
double real_space_delta_loop(const RealSpaceKernel& k, const Particles& p, std::size_t i, const Vec3& rn,
                             const double* w, double* t) {
  const std::size_t n = p.size();
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* z = p.z.data();
  const double xn = rn.x(), yn = rn.y(), zn = rn.z();
  const double xo = x[i], yo = y[i], zo = z[i];
  for (std::size_t j = 0; j < n; ++j) {
    const double vn = psi<kD>(k, xn - x[j], yn - y[j], zn - z[j]);
    const double vo = psi<kD>(k, xo - x[j], yo - y[j], zo - z[j]);
    t[j] = w[j] != 0.0 ? vn - vo : 0.0;
  }
  t[i] = 0.0;  // the moved particle itself (its ψ(0) is not finite)
  return lane_sum(t, n);
}

/// Real-space pair sum Σ_{i<j} w_i w_j ψ(r_i − r_j), rows in index order.
template <int kD>
double real_space_total(const RealSpaceKernel& k, const Particles& p, const double* w, double* t) {
  const std::size_t n = p.size();
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (w[i] == 0.0) continue;
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      const double v = psi<kD>(k, xi - p.x[j], yi - p.y[j], zi - p.z[j]);
      t[j - i - 1] = w[j] != 0.0 ? v : 0.0;
    }
    sum += lane_sum(t, n - i - 1);
  }
  return sum;
}

/// Calls f(std::integral_constant<int, D>) for the run-time degree d (0 or one of kDegrees).
template <typename F>
decltype(auto) with_degree(int d, F&& f) {
  switch (d) {
    case 0: return f(std::integral_constant<int, 0>{});
    case 12: return f(std::integral_constant<int, 12>{});
    case 14: return f(std::integral_constant<int, 14>{});
    case 16: return f(std::integral_constant<int, 16>{});
    case 18: return f(std::integral_constant<int, 18>{});
    case 20: return f(std::integral_constant<int, 20>{});
    case 22: return f(std::integral_constant<int, 22>{});
    case 24: return f(std::integral_constant<int, 24>{});
    case 26: return f(std::integral_constant<int, 26>{});
    case 28: return f(std::integral_constant<int, 28>{});
    case 32: return f(std::integral_constant<int, 32>{});
    case 36: return f(std::integral_constant<int, 36>{});
    case 40: return f(std::integral_constant<int, 40>{});
    case 44: return f(std::integral_constant<int, 44>{});
    default: return f(std::integral_constant<int, 48>{});
  }
}

/// e^{inθ} for n = 0..nmax (one-sided) or n = −nmax..nmax (symmetric, centre at index nmax), by
/// repeated multiplication (deterministic; error ≲ n ulp).
void axis_phases(double theta, int nmax, bool symmetric, double* re, double* im) {
  const double c = std::cos(theta), s = std::sin(theta);
  const int o = symmetric ? nmax : 0;
  re[o] = 1.0;
  im[o] = 0.0;
  for (int n = 1; n <= nmax; ++n) {
    const double pr = re[o + n - 1], pi = im[o + n - 1];
    re[o + n] = pr * c - pi * s;
    im[o + n] = pr * s + pi * c;
  }
  if (symmetric)
    for (int n = 1; n <= nmax; ++n) {
      re[o - n] = re[o + n];
      im[o - n] = -im[o + n];
    }
}

void check_box(const Vec3& L) {
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(L[a]) || L[a] <= 0.0)
      throw InputError("", "box.edges", "expected three positive box edges for the Ewald sum, got " + num(L[a]));
}

/// Number density of the other dipoles seen by one dipole, floored at one neighbour per box.
double neighbour_density(const Vec3& L, std::size_t n) {
  const double others = n > 1 ? static_cast<double>(n - 1) : 1.0;
  return others / L.prod();
}

}  // namespace

// ---- error estimates and parameter choice -------------------------------------------------------

double ewald_real_space_error(const Vec3& L, std::size_t n, double kappa, double r_cut) {
  // Per-particle RMS of the neglected Σ_{r>r_cut} ψ for Poisson-distributed neighbours of density ρ,
  // with ψ ≈ −(4κ³/√π) cos²θ e^{−κ²r²} at large κr:
  //   σ² = ρ ∫_{r_c}^∞ 4πr² ⟨ψ²⟩ dr ≈ (16/5) ρ κ⁴ r_c e^{−2κ²r_c²};
  // and not less than one neighbour just beyond r_cut: |ψ(r_c)| ≤ (4κ³/√π) e^{−κ²r_c²}.
  const double rho = neighbour_density(L, n);
  const double x2 = kappa * kappa * r_cut * r_cut;
  const double k4 = kappa * kappa * kappa * kappa;
  const double stat = std::sqrt(16.0 / 5.0 * rho * k4 * r_cut) * std::exp(-x2);
  const double single = 4.0 * kappa * kappa * kappa / std::sqrt(kPi) * std::exp(-x2);
  return std::max(stat, single);
}

double ewald_reciprocal_error(const Vec3& L, std::size_t n, double kappa, double k_cut) {
  // Per-particle RMS of the neglected reciprocal terms, random positions:
  //   σ² = ρ (4π)² / V Σ_{|k|>k_c} (Ê·k̂)⁴ e^{−k²/(2κ²)} ≈ (8/5) ρ k_c κ² e^{−k_c²/(2κ²)}.
  const double rho = neighbour_density(L, n);
  return std::sqrt(8.0 / 5.0 * rho * k_cut * kappa * kappa) * std::exp(-k_cut * k_cut / (4.0 * kappa * kappa));
}

int ewald_n_max_for(const Vec3& L, std::size_t n, double kappa, double accuracy) {
  check_box(L);
  if (!(accuracy > 0.0 && accuracy < 0.1))
    throw InputError("", "ewald.accuracy", "expected a relative accuracy in (0, 0.1), got " + num(accuracy));
  if (!(std::isfinite(kappa) && kappa > 0.0))
    throw InputError("", "ewald.kappa", "expected a positive finite splitting parameter, got " + num(kappa));
  const double lmax = L.maxCoeff();
  for (int m = 1; m <= kMaxNMax; ++m)
    if (ewald_reciprocal_error(L, n, kappa, 2.0 * kPi * m / lmax) <= accuracy) return m;
  throw InputError("", "ewald.n_max",
                   "expected κ small enough that n_max ≤ " + std::to_string(kMaxNMax) + " reaches the accuracy");
}

EwaldParameters choose_ewald_parameters(const Vec3& L, std::size_t n, double accuracy) {
  check_box(L);
  if (!(accuracy > 0.0 && accuracy < 0.1))
    throw InputError("", "ewald.accuracy", "expected a relative accuracy in (0, 0.1), got " + num(accuracy));
  // Each part gets accuracy/√2, so that the combined per-particle estimate is ≤ accuracy.
  const double part = accuracy / std::sqrt(2.0);
  EwaldParameters p;
  p.r_cut = 0.5 * L.minCoeff();
  // Smallest X = κ r_cut with the real-space estimate ≤ part (decreasing in X for X ≥ 1.3).
  double lo = 1.3, hi = 7.0;
  if (ewald_real_space_error(L, n, hi / p.r_cut, p.r_cut) > part)
    throw InputError("", "ewald.accuracy",
                     "expected an accuracy reachable with κ·r_cut ≤ 7 (about 1e-20 or larger), got " + num(accuracy));
  if (ewald_real_space_error(L, n, lo / p.r_cut, p.r_cut) <= part) {
    hi = lo;
  } else {
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (ewald_real_space_error(L, n, mid / p.r_cut, p.r_cut) <= part) hi = mid; else lo = mid;
    }
  }
  p.kappa = hi / p.r_cut;
  p.n_max = ewald_n_max_for(L, n, p.kappa, part);
  return p;
}

// ---- DipolarEwald -------------------------------------------------------------------------------

DipolarEwald::DipolarEwald(const Vec3& box_edges, const Vec3& direction, double gamma, const EwaldParameters& p,
                           std::vector<char> carries_dipole)
    : L_(box_edges), params_(p) {
  check_box(L_);
  invL_ = L_.cwiseInverse();
  volume_ = L_.prod();
  const double dn = direction.norm();
  if (!std::isfinite(dn) || dn <= 0.0)
    throw InputError("", "field.direction", "expected a non-zero finite field direction");
  dir_ = direction / dn;
  set_gamma(gamma);
  const double half = 0.5 * L_.minCoeff();
  if (params_.minimum_image_only) {
    if (params_.r_cut == 0.0) params_.r_cut = half;
    if (!(params_.r_cut > 0.0 && params_.r_cut <= half * (1 + 1e-12)))
      throw InputError("", "ewald.r_cut",
                       "expected a cut-off in (0, " + num(half) + "] (half the shortest edge), got " + num(params_.r_cut));
    params_.kappa = 0.0;
    params_.n_max = 0;
  } else {
    if (!(std::isfinite(params_.kappa) && params_.kappa > 0.0))
      throw InputError("", "ewald.kappa", "expected a positive finite splitting parameter, got " + num(params_.kappa));
    if (!(params_.r_cut > 0.0 && params_.r_cut <= half * (1 + 1e-12)))
      throw InputError("", "ewald.r_cut",
                       "expected a cut-off in (0, " + num(half) + "] (half the shortest edge), got " + num(params_.r_cut));
    if (params_.kappa * params_.r_cut > 7.0 * (1 + 1e-12))
      throw InputError("", "ewald.kappa",
                       "expected κ·r_cut ≤ 7 (erfc(7) = 4e-23; the real-space polynomial is built for that range), got " +
                           num(params_.kappa * params_.r_cut));
    if (params_.n_max < 1 || params_.n_max > kMaxNMax)
      throw InputError("", "ewald.n_max",
                       "expected an integer in [1, " + std::to_string(kMaxNMax) + "], got " + std::to_string(params_.n_max));
  }
  rc2_ = params_.r_cut * params_.r_cut;
  weight_.resize(carries_dipole.size());
  for (std::size_t i = 0; i < carries_dipole.size(); ++i) {
    weight_[i] = carries_dipole[i] ? 1.0 : 0.0;
    n_dipoles_ += carries_dipole[i] ? 1 : 0;
  }
  pair_terms_.assign(weight_.size() + 8, 0.0);
  build_polynomials();
  build_kvectors();
  build_constants();
}

void DipolarEwald::set_gamma(double gamma) {
  if (!std::isfinite(gamma)) throw InputError("", "field.gamma", "expected a finite dipolar coupling γ");
  gamma_ = gamma;
}

void DipolarEwald::build_polynomials() {
  coef_b_.assign(kMaxDegree + 1, 0.0);
  coef_c_.assign(kMaxDegree + 1, 0.0);
  alpha_ = 2.0 / rc2_;
  if (params_.minimum_image_only) {
    degree_ = 0;
    return;
  }
  // Chebyshev interpolation of b and c on s ∈ [0, r_cut²] (x = s·alpha − 1) at M nodes, in long
  // double; b/κ³ and c/κ⁵ are functions of τ = κ²s ∈ [0, X²] only, with Chebyshev coefficients
  // that fall geometrically (to 1e-16 by degree 20 at X² = 7, 32 at X² = 25, 40 at X² = 42).
  constexpr int M = 128;
  const long double kappa = params_.kappa;
  const long double s_max = 2.0L / static_cast<long double>(alpha_);
  long double fb[M], fc[M], cb[M], cc[M];
  for (int m = 0; m < M; ++m) {
    const long double x = std::cos(kPiL * (m + 0.5L) / M);
    exact_remainders(s_max * 0.5L * (1.0L + x), kappa, fb[m], fc[m]);
  }
  for (int k = 0; k < M; ++k) {
    long double sb = 0, sc = 0;
    for (int m = 0; m < M; ++m) {
      const long double t = std::cos(k * kPiL * (m + 0.5L) / M);
      sb += fb[m] * t;
      sc += fc[m] * t;
    }
    cb[k] = sb * 2 / M;
    cc[k] = sc * 2 / M;
  }
  cb[0] *= 0.5L;
  cc[0] *= 0.5L;
  // Smallest compiled degree whose truncation error Σ_{k>D}|c_k| is ≤ 1e-15 of the function scale
  // (the Horner evaluation in double adds ≈ 2e-16 of the scale: the monomial coefficients in x
  // stay of the size of the function, measured in the unit test).
  const long double kk = kappa * kappa;
  const long double scale_b = kk * kappa, scale_c = kk * kk * kappa;
  degree_ = 0;
  for (int d : kDegrees) {
    long double tb = 0, tc = 0;
    for (int k = d + 1; k < M; ++k) {
      tb += std::fabs(cb[k]);
      tc += std::fabs(cc[k]);
    }
    if (tb <= 1e-15L * scale_b && tc <= 1e-15L * scale_c) {
      degree_ = d;
      break;
    }
  }
  if (degree_ == 0)
    throw InputError("", "ewald.kappa",
                     "expected κ·r_cut ≤ 7 (the real-space polynomial cannot reach double precision beyond), got " +
                         num(params_.kappa * params_.r_cut));
  // Monomial coefficients in x of Σ_{k≤D} c_k T_k(x), by the recurrence T_{k+1} = 2x T_k − T_{k−1}.
  const int D = degree_;
  std::vector<long double> tkm2(D + 1, 0.0L), tkm1(D + 1, 0.0L), tk(D + 1, 0.0L);
  std::vector<long double> ab(D + 1, 0.0L), ac(D + 1, 0.0L);
  tkm2[0] = 1;  // T_0
  tkm1[1] = 1;  // T_1
  ab[0] += cb[0];
  ac[0] += cc[0];
  ab[1] += cb[1];
  ac[1] += cc[1];
  for (int k = 2; k <= D; ++k) {
    for (int m = 0; m <= D; ++m) tk[m] = (m > 0 ? 2 * tkm1[m - 1] : 0.0L) - tkm2[m];
    for (int m = 0; m <= D; ++m) {
      ab[m] += cb[k] * tk[m];
      ac[m] += cc[k] * tk[m];
    }
    tkm2.swap(tkm1);
    tkm1.swap(tk);
  }
  for (int m = 0; m <= D; ++m) {
    coef_b_[m] = static_cast<double>(ab[m]);
    coef_c_[m] = static_cast<double>(ac[m]);
  }
}

int DipolarEwald::column_extent(int nx, int ny) const {
  // |k| ≤ 2π n_max/L_max ⇔ Σ_a (n_a L_max/L_a)² ≤ n_max² (exact integers for a cubic box; the
  // 1e-12 keeps boundary vectors of other boxes from depending on rounding).
  nx = std::abs(nx);
  ny = std::abs(ny);
  if (nx > nx_max_ || ny > ny_max_) return -1;
  const Vec3 scale = L_.maxCoeff() * invL_;
  const double lim = static_cast<double>(params_.n_max) * params_.n_max * (1.0 + 1e-12);
  const double qx = nx * scale.x(), qy = ny * scale.y();
  const double rem = lim - qx * qx - qy * qy;
  if (rem < 0.0) return -1;
  return std::min(nz_max_, static_cast<int>(std::floor(std::sqrt(rem) / scale.z())));
}

void DipolarEwald::build_kvectors() {
  columns_.clear();
  sre_.clear();
  sim_.clear();
  prefactor_.clear();
  nx_max_ = ny_max_ = nz_max_ = 0;
  if (params_.minimum_image_only) {
    phase_old_.assign(6, 0.0);
    phase_new_.assign(6, 0.0);
    return;
  }
  const int nm = params_.n_max;
  const Vec3 scale = L_.maxCoeff() * invL_;  // n_a L_max/L_a: n space scaled to the longest edge
  nx_max_ = static_cast<int>(std::floor(nm / scale.x() * (1.0 + 1e-12)));
  ny_max_ = static_cast<int>(std::floor(nm / scale.y() * (1.0 + 1e-12)));
  nz_max_ = static_cast<int>(std::floor(nm / scale.z() * (1.0 + 1e-12)));
  const double kappa = params_.kappa;
  const double pref = 4.0 * kPi / volume_;
  for (int nx = 0; nx <= nx_max_; ++nx)
    for (int ny = (nx == 0 ? 0 : -ny_max_); ny <= ny_max_; ++ny) {
      const int mz = column_extent(nx, ny);
      if (mz < 0) continue;
      const int lo = (nx == 0 && ny == 0) ? 1 : -mz;
      if (lo > mz) continue;
      columns_.push_back({nx, ny, lo, mz, prefactor_.size()});
      for (int nz = lo; nz <= mz; ++nz) {
        const Vec3 k(2 * kPi * nx * invL_.x(), 2 * kPi * ny * invL_.y(), 2 * kPi * nz * invL_.z());
        const double k2 = k.squaredNorm(), ek = dir_.dot(k);
        prefactor_.push_back(pref * ek * ek / k2 * std::exp(-k2 / (4.0 * kappa * kappa)));
      }
    }
  const std::size_t nk = prefactor_.size();
  sre_.assign(nk, 0.0);
  sim_.assign(nk, 0.0);
  dsre_.assign(nk, 0.0);
  dsim_.assign(nk, 0.0);
  contrib_.assign(nk + 8, 0.0);
  const std::size_t np = 2 * (nx_max_ + 1) + 2 * (2 * ny_max_ + 1) + 2 * (2 * nz_max_ + 1);
  phase_old_.assign(np, 0.0);
  phase_new_.assign(np, 0.0);
}

void DipolarEwald::build_constants() {
  const_per_dipole_ = const_per_pair_ = 0.0;
  if (params_.minimum_image_only) return;
  const long double kappa = params_.kappa;
  const double kd = params_.kappa, rc = params_.r_cut;
  // Self term.
  long double per_dipole = -2.0L * kappa * kappa * kappa / (3.0L * std::sqrt(kPiL));
  // i = j real-space images: every |nL| ≥ L_min > r_cut lies outside the truncated sum, so they
  // are added here exactly (terms with κ|nL| > 8 are < 1e-27 and skipped).
  {
    const double rmax = 8.0 / kd;
    long double img = 0;
    const int mx = static_cast<int>(std::ceil(rmax * invL_.x()));
    const int my = static_cast<int>(std::ceil(rmax * invL_.y()));
    const int mz = static_cast<int>(std::ceil(rmax * invL_.z()));
    for (int a = -mx; a <= mx; ++a)
      for (int b = -my; b <= my; ++b)
        for (int c = -mz; c <= mz; ++c) {
          if (a == 0 && b == 0 && c == 0) continue;
          const Vec3 d(a * L_.x(), b * L_.y(), c * L_.z());
          if (d.norm() > rmax) continue;
          img += exact_psi(d, dir_, kappa);
        }
    per_dipole += 0.5L * img;
  }
  // i = j part of the reciprocal sum beyond the cut-off (|S(k)|² contains N from i = j):
  // N (2π/V) Σ_{k∉K} (Ê·k)²/k² e^{−k²/4κ²}, up to k²/4κ² = 64.
  {
    const double kmax = 16.0 * kd;
    const int mx = static_cast<int>(std::ceil(kmax * L_.x() / (2 * kPi)));
    const int my = static_cast<int>(std::ceil(kmax * L_.y() / (2 * kPi)));
    const int mz = static_cast<int>(std::ceil(kmax * L_.z() / (2 * kPi)));
    long double tail = 0;
    for (int a = -mx; a <= mx; ++a)
      for (int b = -my; b <= my; ++b)
        for (int c = -mz; c <= mz; ++c) {
          if (a == 0 && b == 0 && c == 0) continue;
          if (std::abs(c) <= column_extent(a, b)) continue;  // in the reciprocal sum
          const long double kx = 2 * kPiL * a / L_.x(), ky = 2 * kPiL * b / L_.y(), kz = 2 * kPiL * c / L_.z();
          const long double k2 = kx * kx + ky * ky + kz * kz;
          if (k2 > static_cast<long double>(kmax) * kmax) continue;
          const long double ek = dir_.x() * kx + dir_.y() * ky + dir_.z() * kz;
          tail += ek * ek / k2 * std::exp(-k2 / (4.0L * kappa * kappa));
        }
    per_dipole += 2.0L * kPiL / volume_ * tail;
  }
  const_per_dipole_ = static_cast<double>(per_dipole);
  // Mean-field tail of the truncated real-space pair sum: each pair contributes on average
  // (1/V) ∫_{r>r_c} ⟨ψ⟩ d³r with ⟨ψ⟩_angles = −(4κ³/(3√π)) e^{−κ²r²}:
  //   −(8√π κ r_c e^{−X²})/(3V) − (4π/(3V)) erfc(X),  X = κ r_c.
  const double X = kd * rc;
  const_per_pair_ = -(8.0 * std::sqrt(kPi) * kd * rc * std::exp(-X * X)) / (3.0 * volume_) -
                    4.0 * kPi / (3.0 * volume_) * std::erfc(X);
}

double DipolarEwald::constant_energy() const {
  const double n = static_cast<double>(n_dipoles_);
  return 0.5 * gamma_ * (n * const_per_dipole_ + 0.5 * n * (n - 1) * const_per_pair_);
}

double DipolarEwald::real_space_psi(const Vec3& d) const {
  const RealSpaceKernel k{L_.x(), L_.y(), L_.z(), invL_.x(), invL_.y(), invL_.z(), dir_.x(), dir_.y(), dir_.z(),
                          rc2_, alpha_, coef_b_.data(), coef_c_.data()};
  return with_degree(degree_, [&](auto D) { return psi<decltype(D)::value>(k, d.x(), d.y(), d.z()); });
}

void DipolarEwald::phase_tables(const Vec3& r, double* ph) const {
  const int nx = nx_max_, ny = ny_max_, nz = nz_max_;
  double* xr = ph;
  double* xi = xr + (nx + 1);
  double* yr = xi + (nx + 1);
  double* yi = yr + (2 * ny + 1);
  double* zr = yi + (2 * ny + 1);
  double* zi = zr + (2 * nz + 1);
  axis_phases(2 * kPi * r.x() * invL_.x(), nx, false, xr, xi);
  axis_phases(2 * kPi * r.y() * invL_.y(), ny, true, yr, yi);
  axis_phases(2 * kPi * r.z() * invL_.z(), nz, true, zr, zi);
}

void DipolarEwald::compute_structure_factor(const Particles& p, std::vector<double>& sre,
                                            std::vector<double>& sim) const {
  sre.assign(prefactor_.size(), 0.0);
  sim.assign(prefactor_.size(), 0.0);
  if (params_.minimum_image_only) return;
  std::vector<double> ph(phase_new_.size());
  const int nx = nx_max_, ny = ny_max_;
  for (std::size_t j = 0; j < p.size(); ++j) {
    if (weight_[j] == 0.0) continue;
    phase_tables(p.position(j), ph.data());
    const double* xr = ph.data();
    const double* xi = xr + (nx + 1);
    const double* yr = xi + (nx + 1);
    const double* yi = yr + (2 * ny + 1);
    const double* zr = yi + (2 * ny + 1);
    const double* zi = zr + (2 * nz_max_ + 1);
    for (const Column& c : columns_) {
      const double ar = xr[c.nx] * yr[ny + c.ny] - xi[c.nx] * yi[ny + c.ny];
      const double ai = xr[c.nx] * yi[ny + c.ny] + xi[c.nx] * yr[ny + c.ny];
      const int len = c.nz_hi - c.nz_lo + 1;
      double* outr = sre.data() + c.offset;
      double* outi = sim.data() + c.offset;
      const double* br = zr + nz_max_ + c.nz_lo;
      const double* bi = zi + nz_max_ + c.nz_lo;
      for (int m = 0; m < len; ++m) {
        outr[m] += ar * br[m] - ai * bi[m];
        outi[m] += ar * bi[m] + ai * br[m];
      }
    }
  }
}

void DipolarEwald::rebuild(const Particles& p) {
  if (p.size() != weight_.size())
    throw std::invalid_argument("DipolarEwald::rebuild: particle count differs from the dipole mask");
  compute_structure_factor(p, sre_, sim_);
  pending_ = static_cast<std::size_t>(-1);
}

double DipolarEwald::total_energy(const Particles& p) const {
  if (p.size() != weight_.size())
    throw std::invalid_argument("DipolarEwald::total_energy: particle count differs from the dipole mask");
  const RealSpaceKernel k{L_.x(), L_.y(), L_.z(), invL_.x(), invL_.y(), invL_.z(), dir_.x(), dir_.y(), dir_.z(),
                          rc2_, alpha_, coef_b_.data(), coef_c_.data()};
  std::vector<double> t(p.size() + 1);
  const double real =
      with_degree(degree_, [&](auto D) { return real_space_total<decltype(D)::value>(k, p, weight_.data(), t.data()); });
  double recip = 0.0;
  if (!params_.minimum_image_only) {
    std::vector<double> sre, sim;
    compute_structure_factor(p, sre, sim);
    std::vector<double> c(sre.size());
    for (std::size_t q = 0; q < sre.size(); ++q) c[q] = prefactor_[q] * (sre[q] * sre[q] + sim[q] * sim[q]);
    recip = lane_sum(c.data(), c.size());
  }
  return 0.5 * gamma_ * (real + recip) + constant_energy();
}

double DipolarEwald::reciprocal_delta(const Vec3& r_old, const Vec3& r_new) {
  double* pn = phase_new_.data();
  double* po = phase_old_.data();
  phase_tables(r_new, pn);
  phase_tables(r_old, po);
  const int nx = nx_max_, ny = ny_max_, nz = nz_max_;
  const std::ptrdiff_t oxi = nx + 1, oyr = 2 * (nx + 1), oyi = oyr + 2 * ny + 1, ozr = oyi + 2 * ny + 1,
                       ozi = ozr + 2 * nz + 1;
  const double* __restrict sre = sre_.data();
  const double* __restrict sim = sim_.data();
  const double* __restrict pre = prefactor_.data();
  double* __restrict dsr = dsre_.data();
  double* __restrict dsi = dsim_.data();
  double* __restrict out = contrib_.data();
  for (const Column& c : columns_) {
    const std::ptrdiff_t iy = ny + c.ny;
    const double nr = pn[c.nx] * pn[oyr + iy] - pn[oxi + c.nx] * pn[oyi + iy];
    const double ni = pn[c.nx] * pn[oyi + iy] + pn[oxi + c.nx] * pn[oyr + iy];
    const double orr = po[c.nx] * po[oyr + iy] - po[oxi + c.nx] * po[oyi + iy];
    const double oi = po[c.nx] * po[oyi + iy] + po[oxi + c.nx] * po[oyr + iy];
    const std::ptrdiff_t z0 = nz + c.nz_lo;
    const double* __restrict nzr = pn + ozr + z0;
    const double* __restrict nzi = pn + ozi + z0;
    const double* __restrict ozr_ = po + ozr + z0;
    const double* __restrict ozi_ = po + ozi + z0;
    const std::size_t off = c.offset;
    const int len = c.nz_hi - c.nz_lo + 1;
#pragma GCC ivdep
    for (int m = 0; m < len; ++m) {
      const double dr = (nr * nzr[m] - ni * nzi[m]) - (orr * ozr_[m] - oi * ozi_[m]);
      const double di = (nr * nzi[m] + ni * nzr[m]) - (orr * ozi_[m] + oi * ozr_[m]);
      const std::size_t q = off + static_cast<std::size_t>(m);
      dsr[q] = dr;
      dsi[q] = di;
      out[q] = pre[q] * (2.0 * (sre[q] * dr + sim[q] * di) + (dr * dr + di * di));
    }
  }
  return lane_sum(out, prefactor_.size());
}

double DipolarEwald::delta_energy(const Particles& p, std::size_t i, const Vec3& r_new) {
  if (p.size() != weight_.size() || i >= p.size())
    throw std::invalid_argument("DipolarEwald::delta_energy: particle index or count does not match the dipole mask");
  pending_ = i;
  pending_noop_ = weight_[i] == 0.0;
  if (pending_noop_) return 0.0;
  const RealSpaceKernel k{L_.x(), L_.y(), L_.z(), invL_.x(), invL_.y(), invL_.z(), dir_.x(), dir_.y(), dir_.z(),
                          rc2_, alpha_, coef_b_.data(), coef_c_.data()};
  const double real = with_degree(degree_, [&](auto D) {
    return real_space_delta_loop<decltype(D)::value>(k, p, i, r_new, weight_.data(), pair_terms_.data());
  });
  if (params_.minimum_image_only) return 0.5 * gamma_ * real;
  const double recip = reciprocal_delta(p.position(i), r_new);
  return 0.5 * gamma_ * (real + recip);
}

void DipolarEwald::accept(std::size_t i) {
  if (pending_ != i)
    throw std::logic_error("DipolarEwald::accept: no pending delta_energy for particle " + std::to_string(i));
  pending_ = static_cast<std::size_t>(-1);
  if (pending_noop_ || params_.minimum_image_only) return;
  const std::size_t nk = sre_.size();
  for (std::size_t q = 0; q < nk; ++q) {
    sre_[q] += dsre_[q];
    sim_[q] += dsim_[q];
  }
}

std::vector<double> DipolarEwald::structure_factor() const {
  std::vector<double> s(2 * sre_.size());
  for (std::size_t q = 0; q < sre_.size(); ++q) {
    s[2 * q] = sre_[q];
    s[2 * q + 1] = sim_[q];
  }
  return s;
}

void DipolarEwald::set_structure_factor(const std::vector<double>& s) {
  if (s.size() != 2 * sre_.size())
    throw InputError("", "ewald.structure_factor",
                     "expected " + std::to_string(2 * sre_.size()) + " values (re, im per wave vector), got " +
                         std::to_string(s.size()));
  for (std::size_t q = 0; q < sre_.size(); ++q) {
    sre_[q] = s[2 * q];
    sim_[q] = s[2 * q + 1];
  }
  pending_ = static_cast<std::size_t>(-1);
}

}  // namespace anisodyn
