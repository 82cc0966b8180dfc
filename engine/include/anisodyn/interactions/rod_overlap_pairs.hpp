#pragma once
// The overlap-volume rod potential (interactions/overlap_volume.hpp) as a pair evaluator for
// accumulate_pair_forces and PairForceField: the rods' axes (body z) are taken from the state
// before each evaluation; pairs of other species do not interact (cut-off 0 in the list).
//
// The list treats rods as their axis segments (VerletList, half-length L/2) with the segment
// cut-off of OverlapVolume::segment_cutoff() (≈ D): at (L/D)φ = 1.76 a rod lists about 17
// partners instead of the ~680 whose centres lie within L + D + skin.
//
// Each listed pair is evaluated once (kOncePerPair, pair_forces.hpp): the call for (i, j) gives j's
// force (exactly −F_i) and the energy, and for the few pairs that interact a second call for
// (j, i) gives j's torque. The kernel could return both torques from one call, but its torque
// expressions' multiply-adds may then be fused differently (last bits); the second call keeps the
// forces and torques the bits of evaluating every pair from both sides, for about 3% of a step.
#include <cstddef>
#include <vector>

#include "anisodyn/interactions/overlap_volume.hpp"
#include "anisodyn/interactions/pair_forces.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct RodOverlapPairs {
  static constexpr int kParts = 1;
  static constexpr bool kOncePerPair = true;
  OverlapVolume potential;
  int rod_species = 0;
  std::vector<Vec3> axes;
  std::vector<bool> is_rod;  // the list's skin may pair a rod with another species: they do not interact

  /// Verlet-list cut-offs, distances between axis segments (pass half_lengths() with them): the
  /// segment cut-off between rods, none for other pairs.
  std::vector<double> segment_cutoffs(int nspecies) const {
    std::vector<double> c(static_cast<std::size_t>(nspecies * nspecies), 0.0);
    c[static_cast<std::size_t>(rod_species * nspecies + rod_species)] = potential.segment_cutoff();
    return c;
  }
  /// Verlet-list segment half-lengths: L/2 for the rods, 0 (points) for other species.
  std::vector<double> half_lengths(int nspecies) const {
    std::vector<double> h(static_cast<std::size_t>(nspecies), 0.0);
    h[static_cast<std::size_t>(rod_species)] = 0.5 * potential.settings().length;
    return h;
  }

  void prepare(const State& s) {
    axes.resize(s.particles.size());
    is_rod.resize(s.particles.size());
    for (std::size_t i = 0; i < axes.size(); ++i) {
      axes[i] = s.particles.orientation(i) * Vec3::UnitZ();
      is_rod[i] = s.particles.species[i] == rod_species;
    }
  }

  PairTerm<1> operator()(std::size_t i, std::size_t j, const Vec3& d, double r2) const {
    PairTerm<1> out;
    const double rc = potential.cutoff();
    if (r2 >= rc * rc || !is_rod[i] || !is_rod[j]) return out;
    const RodPairTerm t = potential(d, axes[i], axes[j]);
    out.interacts = t.interacts;
    if (!t.interacts) return out;
    out.force[0] = t.force;
    out.torque = t.torque;
    out.torque_j = potential(-d, axes[j], axes[i]).torque;
    out.energy = t.energy;
    return out;
  }
};

}  // namespace anisodyn
