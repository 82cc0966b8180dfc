#pragma once
// Rigid-body hydrodynamics of a bead model: the 6×6 resistance and diffusion tensors.
//
// Beads of radius a at positions r_i (body frame, relative to the reference point) interact through
// the RPY mobility M (3N×3N). A rigid motion (U, ω) gives bead velocities u_i = U + ω × r_i, the
// bead forces are f = M⁻¹u, and the resistance K maps (U, ω) to the total force and torque about
// the reference point (spec 10 §8.4 step 3):
//   K_tt = Σ_ij Ξ_ij,  K_tr = −Σ_ij Ξ_ij [r_j]×,  K_rt = Σ_ij [r_i]× Ξ_ij,  K_rr = −Σ_ij [r_i]× Ξ_ij [r_j]×.
// The inverse Ξ = M⁻¹ is never formed: a Cholesky factorisation of M is solved for the six rigid
// motions. When the bead set is symmetric under coordinate-plane reflections the problem splits
// into one block per symmetry class of rigid motion (mirror_symmetry.hpp), each solved separately;
// the result is identical to the full solve (tested) at a fraction of the cost.
#include <Eigen/Dense>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::hydro {

using Mat6 = Eigen::Matrix<double, 6, 6>;

struct BeadModel {
  std::vector<Vec3> centres;  // body frame
  double radius = 0.0;        // all beads equal
};

struct ResistanceOptions {
  bool use_symmetry = true;  // split the problem by coordinate-plane mirror symmetry when present
  double eta = 1.0;          // solvent viscosity
};

struct ResistanceResult {
  Mat6 resistance = Mat6::Zero();  // about the origin of the bead coordinates; order (U, ω)
  int symmetry_order = 1;          // size of the mirror group used
  std::size_t largest_block = 0;   // dimension of the largest dense system factorised
};

/// The 6×6 resistance tensor about the origin. Throws RuntimeFailure if the mobility is not
/// positive definite (it always is for RPY with the overlap correction, barring coincident beads).
ResistanceResult rigid_body_resistance(const BeadModel& model, const ResistanceOptions& options = {});

/// Diffusion tensor (k_BT = 1) re-expressed about another reference point p (relative to the old
/// one): D_rr is unchanged, D_tr → D_tr − [p]× D_rr, D_tt → D_tt + D_tr[p]× − [p]× D_rt − [p]× D_rr [p]×.
Mat6 move_reference_point(const Mat6& diffusion, const Vec3& p);

/// The centre of diffusion: the unique point about which the translation–rotation coupling block
/// of the diffusion tensor is symmetric (Harvey & García de la Torre 1980).
Vec3 centre_of_diffusion(const Mat6& diffusion);

/// Largest |D_tr,ij| / √(D_tt,ii D_rr,jj): the roto-translational coupling relative to the diagonal.
double relative_coupling(const Mat6& diffusion);

}  // namespace anisodyn::hydro
