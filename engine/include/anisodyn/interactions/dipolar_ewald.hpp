#pragma once
// Dipolar Ewald summation for identical fixed point dipoles along the field (spec 10 §6).
//
// Every dipole-carrying particle has the same unit dipole along Ê, scaled so that energies come
// out as βU (the prefactor γ/2 of spec §6.1/§6.2 is applied to everything returned):
//   βu_ij = (γ/2) (1 − 3 (Ê·r̂_ij)²) / r_ij³,
// summed over all periodic images with tinfoil boundary conditions (ε' = ∞):
//   βU = (γ/2) [ Σ_{i<j} Σ_n ψ(r_ij + nL) + ½ Σ_i Σ_{n≠0} ψ(nL)
//               + (2π/V) Σ_{k≠0} ((Ê·k)²/k²) e^{−k²/(4κ²)} |S(k)|² − (2κ³/(3√π)) N ],
// ψ(r) = B(r) − (Ê·r)² C(r) as in the spec. docs/ewald.md has the formulas, the parameter choice
// and the measured accuracy and cost.
//
// Implementation notes (details in the .cpp):
//   - real space: a loop over all particles j in index order with the minimum image and r < r_cut
//     (r_cut ≤ half the shortest edge). B and C are split into the bare parts 1/r³, 3/r⁵ (computed
//     exactly, by bare_dipolar_psi of dipolar_pair.hpp, the pair function the analyses share) and
//     remainders b(r²), c(r²), entire functions of r², evaluated as one polynomial each on
//     [0, r_cut²] (degree 12–48 chosen for an error ≲ 1e-15 of their scale; no table look-ups, so
//     the loop vectorises). total_energy and delta_energy use the same pair function,
//     so ΔU equals the difference of totals to rounding.
//   - reciprocal space: the half space of k = 2π(n_x/L_x, n_y/L_y, n_z/L_z) with |k| ≤ 2π n_max/L_max
//     (a sphere in k space: the scaled ellipsoid in n space for a non-cubic box), stored as columns
//     (n_x, n_y) of contiguous n_z, with per-axis phase tables built per call.
//   - sums are accumulated in a fixed 8-lane order, so results are the same doubles whatever the
//     history: delta_energy is a pure function of the positions and the current S(k).
#include <cstddef>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/system/particles.hpp"

namespace anisodyn {

struct EwaldParameters {
  double kappa = 0;    // splitting parameter κ (1/σ)
  double r_cut = 0;    // real-space cut-off, ≤ half the shortest box edge (minimum image)
  int n_max = 0;       // reciprocal cut-off |k| ≤ 2π n_max / L_max (L_max = longest edge)
  /// Smoke-test option (spec §6.2, non-production): bare pair sum, minimum image, r < r_cut
  /// (r_cut = 0 means half the shortest edge), no reciprocal part and no constants.
  bool minimum_image_only = false;
};

/// Estimated RMS error of one particle's real-space energy (in units of γ/2, i.e. per unit dipole
/// pair) from truncating at r_cut, for n_dipoles uncorrelated dipoles beyond r_cut.
double ewald_real_space_error(const Vec3& box_edges, std::size_t n_dipoles, double kappa, double r_cut);
/// Same for the reciprocal sum truncated at |k| ≤ k_cut.
double ewald_reciprocal_error(const Vec3& box_edges, std::size_t n_dipoles, double kappa, double k_cut);
/// Smallest n_max whose reciprocal error estimate is ≤ accuracy for this κ.
int ewald_n_max_for(const Vec3& box_edges, std::size_t n_dipoles, double kappa, double accuracy);

/// Parameters for a requested accuracy (default 1e-5): the estimated RMS error of each particle's
/// energy, real and reciprocal parts combined (each ≤ accuracy/√2), is ≤ accuracy · γ/2
/// (γ/2 = |βu| of a side-by-side contact pair). ΔU of a move is a difference of two such
/// energies: ≤ √2 · accuracy · γ/2 for a jump across the box, much less for small moves (measured
/// in docs/ewald.md). r_cut = half the shortest edge (the real-space sum loops over all dipoles,
/// cheapest for N up to a few thousand), κ from the real-space estimate, n_max from the
/// reciprocal estimate. Throws InputError("", "ewald.accuracy", "expected ...") for accuracy
/// outside (0, 0.1).
EwaldParameters choose_ewald_parameters(const Vec3& box_edges, std::size_t n_dipoles, double accuracy = 1e-5);

class DipolarEwald {
 public:
  /// carries_dipole[i] says whether particle i has a dipole. direction is normalised internally.
  /// Throws InputError for bad parameters (json paths "ewald.*").
  DipolarEwald(const Vec3& box_edges, const Vec3& direction, double gamma, const EwaldParameters& p,
               std::vector<char> carries_dipole);

  /// Recomputes S(k) from scratch from wrapped positions.
  void rebuild(const Particles& p);
  /// Full βU (tinfoil, constants included: self term, i = j image terms, and the mean-field tails
  /// of the truncated sums; see docs/ewald.md). Computes S(k) from p, not from the stored S.
  double total_energy(const Particles& p) const;
  /// βU change if particle i moves from its current position in p to r_new (wrapped). 0 for a
  /// particle without a dipole. Caches what accept() needs. No allocation.
  double delta_energy(const Particles& p, std::size_t i, const Vec3& r_new);
  /// Commits the move evaluated by the last delta_energy call (same i, r_new): updates S(k).
  /// Throws std::logic_error if the last delta_energy call was for another particle or if the move
  /// was already accepted.
  void accept(std::size_t i);

  /// S(k) as plain doubles (re, im interleaved, half-space order) for checkpoints, and its inverse;
  /// after set_structure_factor the object behaves bit-for-bit as before the save.
  std::vector<double> structure_factor() const;
  void set_structure_factor(const std::vector<double>& s);

  const EwaldParameters& parameters() const { return params_; }
  std::size_t wave_vector_count() const { return sre_.size(); }  // half-space count

  double gamma() const { return gamma_; }
  /// Field switching (spec §6.3) at a cycle boundary; S(k) is unaffected. With γ = 0 every ΔU is 0
  /// but still costs a full evaluation: skipping the calls and calling rebuild() at switch-on is
  /// cheaper (docs/ewald.md).
  void set_gamma(double gamma);
  const Vec3& direction() const { return dir_; }
  const Vec3& box_edges() const { return L_; }
  std::size_t particle_count() const { return weight_.size(); }
  std::size_t dipole_count() const { return n_dipoles_; }

  /// The real-space pair function ψ(d) exactly as used in the sums (polynomial remainders), without
  /// γ/2, for the minimum image of d; 0 beyond r_cut. For tests.
  double real_space_psi(const Vec3& d) const;
  /// Degree of the real-space remainder polynomials (0 in minimum_image_only mode).
  int real_space_degree() const { return degree_; }
  /// The constant part of βU (self term, i = j images, tails) for the current N, γ.
  double constant_energy() const;

 private:
  double reciprocal_delta(const Vec3& r_old, const Vec3& r_new);
  void phase_tables(const Vec3& r, double* ph) const;
  void compute_structure_factor(const Particles& p, std::vector<double>& sre, std::vector<double>& sim) const;
  void build_kvectors();
  int column_extent(int nx, int ny) const;  // largest |n_z| in the cut-off, −1 if none
  void build_polynomials();
  void build_constants();

  Vec3 L_, invL_, dir_;
  double gamma_ = 0, volume_ = 0;
  EwaldParameters params_;
  double rc2_ = 0;
  std::size_t n_dipoles_ = 0;
  std::vector<double> weight_;  // 1 for dipoles, 0 otherwise (SoA mask for the real-space loop)

  // real-space remainders b(s), c(s): polynomials of degree degree_ in x = s·alpha_ − 1 ∈ [−1, 1]
  int degree_ = 0;  // 0 in minimum_image_only mode
  double alpha_ = 0;
  std::vector<double> coef_b_, coef_c_;

  // reciprocal space (half space)
  int nx_max_ = 0, ny_max_ = 0, nz_max_ = 0;
  struct Column {
    int nx, ny, nz_lo, nz_hi;
    std::size_t offset;
  };
  std::vector<Column> columns_;
  std::vector<double> sre_, sim_;  // S(k), real and imaginary parts
  std::vector<double> prefactor_;  // (4π/V) (Ê·k)²/k² e^{−k²/4κ²}

  // constants (in units of γ/2): per dipole and per dipole pair
  double const_per_dipole_ = 0, const_per_pair_ = 0;

  // scratch (no allocation per call)
  std::vector<double> dsre_, dsim_, contrib_, pair_terms_;
  std::vector<double> phase_old_, phase_new_;
  std::size_t pending_ = static_cast<std::size_t>(-1);
  bool pending_noop_ = false;
};

}  // namespace anisodyn
