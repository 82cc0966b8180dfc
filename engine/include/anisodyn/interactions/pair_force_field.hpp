#pragma once
// A pair evaluator (interactions/pair_forces.hpp) as the force field an integrator calls
// (integrate/body_forces.hpp): the Verlet list is kept up to date between calls, the per-particle
// storage is reused, and the forces, torques, energy and virial (summed over the parts) are added
// into the BodyForces. An evaluator that needs per-step data of the state (the rods' axes) has
// `void prepare(const State&)`, called before every evaluation.
//
// Integrators take a ForceField by value: pass std::ref(field) so that the list survives.
#include <utility>
#include <vector>

#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/interactions/pair_forces.hpp"
#include "anisodyn/neighbors/verlet_list.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

template <class Eval>
class PairForceField {
 public:
  /// cutoffs[a·nspecies + b]: the pair cut-off of species a and b; skin > 0; half_lengths: the
  /// species' segment half-lengths, when the cut-offs are distances between segments (VerletList).
  PairForceField(Eval eval, std::vector<double> cutoffs, int nspecies, double skin, std::vector<double> half_lengths = {})
      : eval_(std::move(eval)), list_(std::move(cutoffs), nspecies, skin, std::move(half_lengths)) {}

  void operator()(const State& s, BodyForces& out) {
    if constexpr (requires { eval_.prepare(s); }) eval_.prepare(s);
    list_.update(s.box, s.particles);
    sums_ = accumulate_pair_forces(s.box, s.particles, list_, eval_, force_, &torque_, &scratch_);
    for (std::size_t i = 0; i < force_.size(); ++i) {
      out.force[i] += force_[i];
      out.torque[i] += torque_[i];
    }
    out.energy += sums_.energy;
    for (const Mat3& w : sums_.virial) out.virial += w;
  }

  /// Energy and virial, by part, of the last evaluation (DPD's stress splits into its parts).
  const PairSums<Eval::kParts>& last_sums() const { return sums_; }

  /// Calls fn(i, j, d) once for every listed pair i < j, d = minimum-image r_j − r_i, after
  /// preparing the evaluator and updating the list for `s` (for observers of pair statistics).
  template <class Fn>
  void for_each_pair(const State& s, Fn&& fn) {
    if constexpr (requires { eval_.prepare(s); }) eval_.prepare(s);
    list_.update(s.box, s.particles);
    for (std::size_t i = 0; i < s.particles.size(); ++i)
      for (const std::int32_t j : list_.partners_above(i))
        fn(i, static_cast<std::size_t>(j), s.box.min_image(s.particles.position(static_cast<std::size_t>(j)) - s.particles.position(i)));
  }

  const Eval& evaluator() const { return eval_; }
  Eval& evaluator() { return eval_; }
  const VerletList& list() const { return list_; }

 private:
  Eval eval_;
  VerletList list_;
  std::vector<Vec3> force_, torque_;
  PairScratch<Eval::kParts> scratch_;
  PairSums<Eval::kParts> sums_;
};

}  // namespace anisodyn
