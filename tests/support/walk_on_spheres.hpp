#pragma once
// Electrostatic capacitance of a convex body K by walk on spheres (Muller, Ann. Math. Stat. 27, 569
// (1956); for capacitance Zhou, Szabo, Douglas & Hubbard, J. Chem. Phys. 100, 3821 (1994)), with
// control variates. A test-side reference, independent of the shell-model code: docs/validation.md
// checks the shell model's hydrodynamic radius against the bound R_h ≥ C with it. Units: a sphere's C
// is its radius.
//
// Launch. Brownian motion coming from infinity first touches an ellipsoid B ⊃ K at a point drawn
// from the equilibrium (capacitary) distribution μ_B of B. That distribution is the image of the
// uniform distribution on the unit sphere under x ↦ diag(b)x (the charge of a conducting ellipsoid
// fills a thin homoeoid). Hence
//   C_K = C_B · P(a walker started from μ_B hits K before escaping to infinity),
// with C_B = 2/χ in closed form (hydro_theory.hpp).
//
// Walk. At x, the largest ball around x that misses K has radius d(x), the distance to K; the
// walker jumps to a uniform point on its sphere and stops as a hit once d < ε. Outside a sphere S
// of radius R ≥ circumradius(K) about the origin it comes back to S with probability R/|x| (and
// escapes otherwise), at a point drawn from the exterior harmonic measure of S, density
// ∝ (|x|² − R²)/|x − y|³, sampled in closed form.
//
// ε-shell bias. A walk stops as a hit when the Brownian path hits K (always) or only passes within ε
// of it (sometimes), so the estimate lies between C(K) and C(K_ε), K_ε the ε-neighbourhood. For K
// convex and containing the ball of radius r_in about the origin, K_ε ⊂ (1 + ε/r_in)K, so
//   0 ≤ bias ≤ (ε/r_in)·C(K).
// WalkOptions::epsilon is ε/r_in: it is the bound on the relative bias.
//
// Control variates. The potential g_j of a unit charge placed strictly inside K (a point, a ring) is
// harmonic and bounded outside K and vanishes at infinity, so by optional stopping
//   E[1{hit}·g_j(X_stop)] = E[g_j(X_0)] = ∫ g_j dμ_B = 1/C_B,
// the last step because the potential of B's equilibrium charge is 1/C_B everywhere inside B
// (reciprocity). This holds exactly at the ε-stopping point. With coefficients β fitted on separate
// pilot walks (least squares 1 ≈ Σ_j β_j g_j at the pilot hits: the method of fundamental solutions),
//   Ĉ = C_B · mean[1{hit}·(1 − Σ_j β_j g_j(X_stop))] + Σ_j β_j
// is unbiased for any β; a good fit only shrinks the variance. The plain estimate C_B·hits/walks
// comes from the same walks.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/core/types.hpp"
#include "hydro_theory.hpp"

namespace anisodyn::testing_support {

/// A convex body that contains the origin.
class ConvexBody {
 public:
  virtual ~ConvexBody() = default;
  virtual double distance(const Vec3& x) const = 0;  // 0 inside
  virtual double inradius() const = 0;               // largest ball about the origin inside
  virtual double circumradius() const = 0;           // smallest ball about the origin around
};

/// The ellipsoid the walks start from, with its capacitance. It must contain the body.
struct LaunchEllipsoid {
  Vec3 semi_axes;
  double capacitance;
  explicit LaunchEllipsoid(const Vec3& b)
      : semi_axes(b), capacitance(theory::ellipsoid_capacitance(b.x(), b.y(), b.z())) {}
};

/// Potential of a unit charge distribution strictly inside the body: one control variate.
using UnitChargePotential = std::function<double(const Vec3&)>;

struct WalkOptions {
  std::uint64_t walks = 1'000'000;
  std::uint64_t pilot_walks = 50'000;  // separate walks that fit the control-variate coefficients
  double epsilon = 1e-6;               // stopping shell ε / inradius: the bound on the relative bias
  double return_radius = 0.0;          // radius of S; 0: the body's circumradius (the least allowed)
  std::uint64_t seed = 1;
};

struct CapacitanceEstimate {
  double value = 0.0, standard_error = 0.0;              // with the control variates
  double plain_value = 0.0, plain_standard_error = 0.0;  // C_B × hit fraction, the same walks
  double fitted_charge = 0.0;                            // Σ β_j
  double bias_bound = 0.0;                               // 0 ≤ ε-shell bias ≤ bias_bound × C
  double launch_capacitance = 0.0;
  std::uint64_t walks = 0, hits = 0;
};

namespace wos_detail {

constexpr std::uint64_t kBlock = 4096;                 // walks per generator stream
constexpr std::uint64_t kPilotStreams = 1ull << 40;    // pilot streams never meet the main run's

/// Uniform point on the unit sphere (Marsaglia, Ann. Math. Stat. 43, 645 (1972)).
inline Vec3 uniform_unit_vector(Rng& rng) {
  for (;;) {
    const double u = 2.0 * rng.uniform() - 1.0, v = 2.0 * rng.uniform() - 1.0, s = u * u + v * v;
    if (s >= 1.0 || s == 0.0) continue;
    const double f = 2.0 * std::sqrt(1.0 - s);
    return {u * f, v * f, 1.0 - 2.0 * s};
  }
}

/// cos θ between x̂ and the return point on S, for q = R/|x| < 1 and ξ uniform in [0, 1): the
/// inverse of the CDF of the density ∝ (1 + q² − 2qu)^(−3/2) on [−1, 1]. Written in t = 2ξ − 1 so
/// that it stays exact as q → 0 (where the density becomes uniform).
inline double return_cosine(double q, double xi) {
  const double t = 2.0 * xi - 1.0, a = 1.0 + q * t;
  const double u = (t + 0.5 * q * (t * t + 3.0) + q * q * t + 0.5 * q * q * q * (t * t - 1.0)) / (a * a);
  return std::clamp(u, -1.0, 1.0);
}

/// Point where a walker at x outside the sphere of radius R comes back to it (given that it does).
inline Vec3 exterior_return_point(const Vec3& x, double R, Rng& rng) {
  const double r = x.norm();
  const Vec3 e = x / r;
  const double u = return_cosine(R / r, rng.uniform());
  Vec3 w;  // a unit vector ⟂ e at a uniform azimuth
  do {
    const Vec3 v = uniform_unit_vector(rng);
    w = v - v.dot(e) * e;
  } while (w.squaredNorm() < 1e-12);
  return R * (u * e + std::sqrt(1.0 - u * u) * w.normalized());
}

struct WalkEnd {
  bool hit;
  Vec3 where;
};

inline WalkEnd walk_to_body(Vec3 x, const ConvexBody& body, double R, double eps, Rng& rng) {
  for (;;) {
    const double r = x.norm();
    if (r > R) {
      if (rng.uniform() * r >= R) return {false, x};
      x = exterior_return_point(x, R, rng);
    }
    const double d = body.distance(x);
    if (d < eps) return {true, x};
    x += d * uniform_unit_vector(rng);
  }
}

/// Runs `walks` walks from the launch ellipsoid, kBlock per generator stream (first_stream + block),
/// so that the outcome does not depend on the thread count; visit(block, end) sees each walk's end
/// and may write only to storage of its own block.
template <class Visit>
void run_walks(std::uint64_t walks, std::uint64_t first_stream, const ConvexBody& body, const LaunchEllipsoid& launch,
               const WalkOptions& opt, Visit&& visit) {
  const double R = std::max(opt.return_radius, body.circumradius()), eps = opt.epsilon * body.inradius();
  const auto blocks = static_cast<std::int64_t>((walks + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = static_cast<std::uint64_t>(b);
    Rng rng(opt.seed, first_stream + block);
    const std::uint64_t n = std::min(kBlock, walks - block * kBlock);
    for (std::uint64_t k = 0; k < n; ++k)
      visit(block, walk_to_body(launch.semi_axes.cwiseProduct(uniform_unit_vector(rng)), body, R, eps, rng));
  }
}

inline std::size_t block_count(std::uint64_t walks) { return static_cast<std::size_t>((walks + kBlock - 1) / kBlock); }

inline Eigen::VectorXd potentials_at(const std::vector<UnitChargePotential>& charges, const Vec3& x) {
  Eigen::VectorXd g(static_cast<Eigen::Index>(charges.size()));
  for (std::size_t j = 0; j < charges.size(); ++j) g(static_cast<Eigen::Index>(j)) = charges[j](x);
  return g;
}

/// β minimising Σ over the pilot hits of (1 − Σ_j β_j g_j(X))².
inline Eigen::VectorXd fit_charges(const std::vector<UnitChargePotential>& charges, const ConvexBody& body,
                                   const LaunchEllipsoid& launch, const WalkOptions& opt) {
  if (charges.empty() || opt.pilot_walks == 0) return Eigen::VectorXd::Zero(static_cast<Eigen::Index>(charges.size()));
  std::vector<std::vector<Vec3>> hits(block_count(opt.pilot_walks));
  run_walks(opt.pilot_walks, kPilotStreams, body, launch, opt, [&](std::uint64_t block, const WalkEnd& end) {
    if (end.hit) hits[block].push_back(end.where);
  });
  std::vector<Vec3> points;
  for (const auto& h : hits) points.insert(points.end(), h.begin(), h.end());
  Eigen::MatrixXd A(static_cast<Eigen::Index>(points.size()), static_cast<Eigen::Index>(charges.size()));
  for (std::size_t i = 0; i < points.size(); ++i) A.row(static_cast<Eigen::Index>(i)) = potentials_at(charges, points[i]).transpose();
  return A.completeOrthogonalDecomposition().solve(Eigen::VectorXd::Ones(A.rows()));
}

struct BlockSums {
  std::uint64_t hits = 0;
  double residual = 0.0, residual2 = 0.0;  // Σ r and Σ r², r = 1{hit}(1 − β·g(X))
};

}  // namespace wos_detail

/// C of `body` by walk on spheres from `launch` (which must contain the body), with the potentials
/// of `charges` (unit charges inside the body; may be empty) as control variates.
inline CapacitanceEstimate walk_on_spheres_capacitance(const ConvexBody& body, const LaunchEllipsoid& launch,
                                                       const std::vector<UnitChargePotential>& charges,
                                                       const WalkOptions& opt) {
  using namespace wos_detail;
  const Eigen::VectorXd beta = fit_charges(charges, body, launch, opt);

  std::vector<BlockSums> sums(block_count(opt.walks));
  run_walks(opt.walks, 0, body, launch, opt, [&](std::uint64_t block, const WalkEnd& end) {
    if (!end.hit) return;
    const double r = 1.0 - beta.dot(potentials_at(charges, end.where));
    BlockSums& s = sums[block];
    s.hits += 1;
    s.residual += r;
    s.residual2 += r * r;
  });
  BlockSums total;
  for (const auto& s : sums) {  // in block order: the same sum whatever the thread count
    total.hits += s.hits;
    total.residual += s.residual;
    total.residual2 += s.residual2;
  }

  const double n = static_cast<double>(opt.walks), CB = launch.capacitance;
  const double mean = total.residual / n;
  const double variance = std::max(0.0, (total.residual2 - n * mean * mean) / (n - 1.0));
  const double p = static_cast<double>(total.hits) / n;
  CapacitanceEstimate out;
  out.fitted_charge = beta.sum();
  out.value = CB * mean + out.fitted_charge;
  out.standard_error = CB * std::sqrt(variance / n);
  out.plain_value = CB * p;
  out.plain_standard_error = CB * std::sqrt(p * (1.0 - p) / n);
  out.bias_bound = opt.epsilon;
  out.launch_capacitance = CB;
  out.walks = opt.walks;
  out.hits = total.hits;
  return out;
}

}  // namespace anisodyn::testing_support
