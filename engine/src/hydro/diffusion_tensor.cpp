#include "anisodyn/hydro/diffusion_tensor.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/extrapolation.hpp"

namespace anisodyn::hydro {

namespace {

/// Cuboid shells fit whole grid intervals n across the thinnest edge T (σ_b = T/(2n)), so the bead
/// spacing on the thin faces equals 2σ_b exactly and the extrapolation sees no rounding jitter.
/// Rounding can merge neighbouring radii; the series then takes every n in the range.
std::set<double> cuboid_bead_radii(double T, const std::vector<double>& wanted) {
  std::set<double> radii;
  for (double s : wanted) radii.insert(T / (2.0 * std::max(2.0, std::round(T / (2.0 * s)))));
  if (radii.size() < wanted.size()) {
    const int n_fine = static_cast<int>(std::round(T / (2.0 * wanted.front())));
    const int n_coarse = static_cast<int>(std::max(2.0, std::round(T / (2.0 * wanted.back()))));
    for (int n = n_coarse; n <= n_fine && radii.size() < wanted.size(); ++n) radii.insert(T / (2.0 * n));
  }
  return radii;
}

/// Largest σ_b whose shell has at least `beads` beads (bisection on the bead count, which falls
/// with σ_b).
double bead_radius_for_count(const HydroShape& shape, std::size_t beads, ShellConstruction construction) {
  double lo = 1e-4 * thinnest_dimension(shape), hi = thinnest_dimension(shape);
  for (int it = 0; it < 60; ++it) {
    const double mid = std::sqrt(lo * hi);
    if (construction(shape, mid).size() >= beads) lo = mid; else hi = mid;
  }
  return lo;
}

}  // namespace

Vec6 DiffusionTensorResult::relative_error_of(ExtrapolationOrder order) const {
  const Mat6& chosen = diffusion_of(order);
  const Mat6& reference = order == ExtrapolationOrder::Linear ? quadratic_diffusion
                          : cubic_diffusion                   ? *cubic_diffusion
                                                              : linear_diffusion;
  Vec6 err;
  for (int i = 0; i < 6; ++i) err[i] = std::abs(reference(i, i) - chosen(i, i)) / chosen(i, i);
  return err;
}

std::string DiffusionTensorResult::error_reference_of(ExtrapolationOrder order) const {
  if (order == ExtrapolationOrder::Linear) return "quadratic";
  return cubic_diffusion ? "cubic" : "linear";
}

std::vector<double> choose_bead_radii(const HydroShape& shape, const ShellSeries& series, ShellConstruction construction) {
  if (series.count < 3) throw InputError("an extrapolation to zero bead size needs at least 3 shell resolutions");
  if (!(series.size_ratio > 1.0)) throw InputError("the coarsest/finest bead-size ratio must exceed 1");
  const double finest = bead_radius_for_count(shape, series.max_beads, construction);
  const double coarsest_allowed = 0.25 * thinnest_dimension(shape);
  if (finest * series.size_ratio > coarsest_allowed) {
    const std::size_t needed = construction(shape, coarsest_allowed / series.size_ratio).size();
    throw InputError("max_beads = " + std::to_string(series.max_beads) + " is too few beads for an extrapolation: "
                     "the coarsest shell must resolve the thinnest dimension (σ_b ≤ thickness/4), which needs "
                     "at least " + std::to_string(needed) + " beads in the finest shell");
  }
  std::vector<double> wanted;
  for (int k = 0; k < series.count; ++k) wanted.push_back(finest * std::pow(series.size_ratio, k / double(series.count - 1)));
  const std::set<double> radii = shape.kind == HydroShapeKind::Cuboid ? cuboid_bead_radii(shape.edges.minCoeff(), wanted)
                                                                      : std::set<double>(wanted.begin(), wanted.end());
  if (radii.size() < 3)
    throw InputError("the bead radii collapse to fewer than 3 distinct shells after fitting the cuboid grid; "
                     "raise max_beads or size_ratio");
  return {radii.rbegin(), radii.rend()};  // coarsest first
}

DiffusionTensorResult compute_diffusion_tensor(const HydroShape& shape, const std::vector<double>& bead_radii,
                                               const ResistanceOptions& options, const ShellProgress& progress,
                                               ShellConstruction construction, ExtrapolationRule rule) {
  DiffusionTensorResult out;
  for (std::size_t k = 0; k < bead_radii.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    ShellSolution s;
    s.sigma_b = bead_radii[k];
    const BeadModel model{construction(shape, s.sigma_b), s.sigma_b};
    s.beads = model.centres.size();
    const ResistanceResult r = rigid_body_resistance(model, options);
    s.symmetry_order = r.symmetry_order;
    s.largest_block = r.largest_block;
    const Mat6 diffusion_about_origin = r.resistance.inverse();
    s.centre_of_diffusion = centre_of_diffusion(diffusion_about_origin);
    s.diffusion = move_reference_point(diffusion_about_origin, s.centre_of_diffusion);
    s.resistance = s.diffusion.inverse();
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.shells.push_back(s);
    if (progress) progress(s, k, bead_radii.size());
  }

  std::vector<double> sigma;
  for (const auto& s : out.shells) sigma.push_back(s.sigma_b);
  Mat6 linear = Mat6::Zero(), quadratic = Mat6::Zero(), cubic = Mat6::Zero();
  bool has_cubic = true;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      std::vector<double> y;
      for (const auto& s : out.shells) y.push_back(s.resistance(i, j));
      const auto e = extrapolate_to_zero_size(sigma, y);
      linear(i, j) = e.linear;
      quadratic(i, j) = e.quadratic;
      if (e.cubic) cubic(i, j) = *e.cubic; else has_cubic = false;
    }
  out.linear_diffusion = linear.inverse();
  out.quadratic_diffusion = quadratic.inverse();
  if (has_cubic) out.cubic_diffusion = cubic.inverse();
  out.rule = rule;
  out.extrapolation = rule == ExtrapolationRule::Quadratic ? ExtrapolationOrder::Quadratic : ExtrapolationOrder::Linear;
  if (rule == ExtrapolationRule::Auto) {
    // A fit whose tensor is not positive has no meaningful estimate and is never chosen.
    const auto estimate = [&](ExtrapolationOrder order) {
      const Mat6& D = out.diffusion_of(order);
      if (!D.allFinite() || D.diagonal().minCoeff() <= 0.0) return std::numeric_limits<double>::infinity();
      return out.relative_error_of(order).maxCoeff();
    };
    out.extrapolation = choose_extrapolation(estimate(ExtrapolationOrder::Linear), estimate(ExtrapolationOrder::Quadratic));
  }
  const ExtrapolationOrder extrapolation = out.extrapolation;
  out.resistance = extrapolation == ExtrapolationOrder::Linear ? linear : quadratic;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> y;
    for (const auto& s : out.shells) y.push_back(s.centre_of_diffusion[a]);
    out.centre_of_diffusion[a] = extrapolate_to_zero_size(sigma, y).intercept(extrapolation);
  }
  out.diffusion = out.diffusion_of(extrapolation);
  out.relative_error = out.relative_error_of(extrapolation);
  out.relative_coupling = relative_coupling(out.diffusion);
  if (!out.diffusion.allFinite() || out.diffusion.diagonal().minCoeff() <= 0.0)
    throw RuntimeFailure("the extrapolated diffusion tensor is not positive: the shells are too coarse for a " +
                         extrapolation_name(extrapolation) + " extrapolation");
  return out;
}

}  // namespace anisodyn::hydro
