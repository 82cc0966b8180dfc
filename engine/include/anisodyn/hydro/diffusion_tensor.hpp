#pragma once
// The infinite-dilution diffusion tensor of a rigid body from a series of shell models.
//
// For each bead radius σ_b: build the shell, solve for the 6×6 resistance about the centroid, find
// the centre of diffusion and re-express the tensors there. The resistance about the centre of
// diffusion is then extrapolated element by element, linearly in σ_b, to σ_b → 0 and inverted
// (friction is the quantity that is linear in σ_b: for a sphere shell K = 6πηR(1 + c σ_b/R) to
// first order). The estimate of the extrapolation error of each diffusion coefficient is the
// relative difference between the linear and the quadratic extrapolation.
#include <functional>
#include <vector>

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
  Mat6 resistance = Mat6::Zero();     // extrapolated, about the centre of diffusion
  Mat6 diffusion = Mat6::Zero();      // its inverse (k_BT = 1)
  Vec3 centre_of_diffusion = Vec3::Zero();  // extrapolated, relative to the body centre
  Mat6 quadratic_diffusion = Mat6::Zero();  // from the element-wise quadratic extrapolation instead
  Vec6 relative_error = Vec6::Zero();  // |linear − quadratic| / linear for each diagonal D
  double relative_coupling = 0.0;      // largest |D_tr,ij|/√(D_tt,ii D_rr,jj)

  Vec3 D_trans() const { return diffusion.diagonal().head<3>(); }
  Vec3 D_rot() const { return diffusion.diagonal().tail<3>(); }
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
                                               ShellConstruction construction = &shell_beads);

}  // namespace anisodyn::hydro
