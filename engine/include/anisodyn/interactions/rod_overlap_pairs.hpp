#pragma once
// The overlap-volume rod potential (interactions/overlap_volume.hpp) as a pair evaluator for
// accumulate_pair_forces and PairForceField: the rods' axes (body z) are taken from the state
// before each evaluation; pairs of other species do not interact (cut-off 0 in the list).
#include <cstddef>
#include <vector>

#include "anisodyn/interactions/overlap_volume.hpp"
#include "anisodyn/interactions/pair_forces.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

struct RodOverlapPairs {
  static constexpr int kParts = 1;
  OverlapVolume potential;
  int rod_species = 0;
  std::vector<Vec3> axes;
  std::vector<bool> is_rod;  // the list's skin may pair a rod with another species: they do not interact

  /// Verlet-list cut-offs: L + D between rods, none for other pairs.
  std::vector<double> cutoffs(int nspecies) const {
    std::vector<double> c(static_cast<std::size_t>(nspecies * nspecies), 0.0);
    c[static_cast<std::size_t>(rod_species * nspecies + rod_species)] = potential.cutoff();
    return c;
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
    out.force[0] = t.force;
    out.torque = t.torque;
    out.energy = t.energy;
    return out;
  }
};

}  // namespace anisodyn
