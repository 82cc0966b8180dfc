#pragma once
// The infinite-dilution diffusion tensor of a rigid body from a series of shell models.
//
// For each bead radius σ_b: build the shell, solve for the 6×6 resistance about the centroid, find
// the centre of diffusion and re-express the tensors there. The resistance about the centre of
// diffusion is then extrapolated element by element to σ_b → 0 (a least-squares polynomial in σ_b
// of the chosen order, linear or quadratic) and inverted (friction is the quantity that is linear
// in σ_b to first order: for a sphere shell K = 6πηR(1 + c σ_b/R + …)). The estimate of the
// extrapolation error of each diffusion coefficient compares the chosen fit with the next higher
// one (relative_error_of).
#include <functional>
#include <optional>
#include <vector>

#include "anisodyn/hydro/extrapolation.hpp"
#include "anisodyn/hydro/rigid_body_resistance.hpp"
#include "anisodyn/hydro/shell_surface.hpp"

namespace anisodyn::hydro {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct ShellSolution {
  double sigma_b = 0.0;
  std::size_t beads = 0;
  int symmetry_order = 1;
  std::size_t largest_block = 0;
  Vec3 centre_of_diffusion = Vec3::Zero();
  Mat6 resistance = Mat6::Zero();  // about the centre of diffusion
  Mat6 diffusion = Mat6::Zero();   // about the centre of diffusion, k_BT = 1
  double seconds = 0.0;
};

struct DiffusionTensorResult {
  std::vector<ShellSolution> shells;
  ExtrapolationRule rule = kDefaultExtrapolation;            // what was asked for
  ExtrapolationOrder extrapolation = ExtrapolationOrder::Linear;  // the fit behind resistance and diffusion
  Mat6 resistance = Mat6::Zero();     // extrapolated, about the centre of diffusion
  Mat6 diffusion = Mat6::Zero();      // its inverse (k_BT = 1)
  Vec3 centre_of_diffusion = Vec3::Zero();  // extrapolated, relative to the body centre
  // Every fit, whichever is chosen: the inverse of the element-wise extrapolated resistance.
  Mat6 linear_diffusion = Mat6::Zero();
  Mat6 quadratic_diffusion = Mat6::Zero();
  std::optional<Mat6> cubic_diffusion;  // with ≥ 4 distinct bead radii
  Vec6 relative_error = Vec6::Zero();  // relative_error_of(extrapolation)
  double relative_coupling = 0.0;      // largest |D_tr,ij|/√(D_tt,ii D_rr,jj)

  Vec3 D_trans() const { return diffusion.diagonal().head<3>(); }
  Vec3 D_rot() const { return diffusion.diagonal().tail<3>(); }

  const Mat6& diffusion_of(ExtrapolationOrder order) const {
    return order == ExtrapolationOrder::Linear ? linear_diffusion : quadratic_diffusion;
  }
  /// The error estimate of each diagonal D of the given fit: its relative difference from the
  /// next higher fit. Linear: |linear − quadratic|/linear. Quadratic: |quadratic − cubic|/quadratic
  /// with ≥ 4 distinct radii, else |quadratic − linear|/quadratic.
  Vec6 relative_error_of(ExtrapolationOrder order) const;
  /// The fit relative_error_of(order) compares with: "quadratic" or "cubic" (or "linear").
  std::string error_reference_of(ExtrapolationOrder order) const;
};

struct ShellSeries {
  int count = 5;                 // number of bead radii
  std::size_t max_beads = 6000;  // beads in the finest shell (approximately)
  double size_ratio = 2.0;       // coarsest σ_b / finest σ_b
};

/// Bead radii for an extrapolation: `count` values spaced geometrically from the finest (whose
/// shell has about max_beads beads) up to size_ratio times it. The coarsest must resolve the body
/// (σ_b ≤ thinnest/4); InputError when max_beads is too small for that.
std::vector<double> choose_bead_radii(const HydroShape& shape, const ShellSeries& series,
                                      ShellConstruction construction = &shell_beads);

using ShellProgress = std::function<void(const ShellSolution&, std::size_t index, std::size_t total)>;

DiffusionTensorResult compute_diffusion_tensor(const HydroShape& shape, const std::vector<double>& bead_radii,
                                               const ResistanceOptions& options = {},
                                               const ShellProgress& progress = nullptr,
                                               ShellConstruction construction = &shell_beads,
                                               ExtrapolationRule extrapolation = kDefaultExtrapolation);

}  // namespace anisodyn::hydro
