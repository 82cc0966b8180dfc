#pragma once
// The closure check of spec 20 §9 (spec 50 §9.4, I4) along aligned → isotropic decays: per frame,
// from the rod axes û_n of N rods,
//   S = (1/N) Σ û û,
//   S⁽⁴⁾:S with (S⁽⁴⁾:S)_αβ = Σ_γδ ⟨û_α û_β û_γ û_δ⟩ S_γδ = (1/N) Σ_n û_α û_β (û·S·û)
//     (computed in this form, never forming the 81 components of S⁽⁴⁾),
//   the closure (1/5)[2 S·S + 3 S (S:S)] of the Doi–Edwards–Kuzuu equation (spec 20 §8.3).
// Both sides equal ẑẑ at perfect alignment along ẑ and I/9 at isotropy (S = I/3, isotropic S⁽⁴⁾).
// The stage (anisodyn-closure) averages them over replicas on the common time grid (spec 50 §0).
#include <cstddef>
#include <string>
#include <vector>

#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/core/types.hpp"

namespace anisodyn::analysis {

/// S⁽⁴⁾:S = (1/N) Σ_n û_n û_n (û_n·S·û_n) for the axes and their order tensor S.
Mat3 fourth_moment_contraction(const std::vector<Vec3>& axes, const Mat3& order);
/// (1/5)[2 S·S + 3 S (S:S)].
Mat3 closure_approximation(const Mat3& order);

struct ClosureSides {
  Mat3 order = Mat3::Zero();       // S
  Mat3 exact = Mat3::Zero();       // S⁽⁴⁾:S
  Mat3 closure = Mat3::Zero();     // (1/5)[2 S·S + 3 S (S:S)]
};
ClosureSides closure_sides(const std::vector<Vec3>& axes);

/// The per-frame series of the stage, in the order of closure_series_names().
const std::vector<std::string>& closure_series_names();

struct ClosureSeries {
  std::string name;
  std::vector<double> mean, error;  // on the common grid; SE over replicas (NaN for one)
};

struct ClosureResult {
  std::vector<double> time;
  std::vector<ClosureSeries> series;
  std::size_t replicas = 0, rods = 0;
};

class ClosureAnalysis {
 public:
  explicit ClosureAnalysis(int rod_axis);
  /// Adds one replica: the closure sides of the rods of `species_index` at every frame.
  void accumulate(const Trajectory& t, int species_index);
  /// Means over replicas on the common grid (each replica interpolated onto it).
  ClosureResult compute(const std::vector<double>& common_time) const;

 private:
  int rod_axis_;
  std::size_t rods_ = 0;
  std::vector<std::vector<double>> times_;                 // [replica][frame]
  std::vector<std::vector<std::vector<double>>> values_;   // [replica][series][frame]
};

}  // namespace anisodyn::analysis
