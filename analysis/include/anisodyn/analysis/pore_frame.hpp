#pragma once
// The pore-frame mean squared displacements of spec 40 §9: a body in a cylindrical pore along z
// (axis through `axis`), its centre's displacement in each frame interval turned into the pore
// frame of the interval's start, P(θ_{n−1}) δX^c_n with θ = atan2(y^c, x^c): x^p radial, y^p
// azimuthal, z^p axial. Each frame n starts a sub-trajectory of the next `lags` intervals, assigned
// to the bin of its β = d_n/(R_pore − R) (d the distance from the axis), bins of `bin_width`; the
// MSD per bin and lag is the mean over the bin's sub-trajectories.
#include <cstddef>
#include <span>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis {

struct PoreFrameBins {
  double bin_width = 0.05;
  std::size_t lags = 25;
  /// Per bin: the number of sub-trajectories, and per lag k = 1 … lags and component the sums of
  /// the squared displacements and of their squares ([bin][k − 1]).
  std::vector<std::size_t> count;
  std::vector<std::vector<Vec3>> sum, sum2;

  /// The bin of β (β < 0 → 0; no upper limit: bins are added as needed).
  std::size_t bin(double beta) const;
  void add(std::size_t bin, std::size_t lag, const Vec3& squared);
  /// Adds another run's sums.
  void merge(const PoreFrameBins& other);

 private:
  void grow(std::size_t bin);
};

/// The pore-frame displacements P(θ_{n−1}) (X_n − X_{n−1}) of a path of unwrapped centres.
std::vector<Vec3> pore_frame_displacements(std::span<const Vec3> centre, const Vec3& axis);

/// Accumulates the sub-trajectories of one run into `bins` (gap = R_pore − R).
void accumulate_pore_bins(std::span<const Vec3> centre, const Vec3& axis, double gap, PoreFrameBins& bins);

}  // namespace anisodyn::analysis
