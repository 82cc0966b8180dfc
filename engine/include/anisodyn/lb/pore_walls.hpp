#pragma once
// The excluded-volume wall of spec 40 §6's cylindrical pore: fixed wall beads of radius r_p on the
// cylinder of radius R_pore + r_p about the axis (along z, through the box's centre in x and y),
// in rings a little over `spacing` apart along z (a whole number of rings per box length, so the
// pore is periodic) with round(2π(R_pore + r_p)/spacing) beads each, and the purely repulsive WCA
// between them and the raspberries' inner-layer beads (radius r_r): σ = r_r + r_p, ε, cut at
// 2^{1/6}σ. A raspberry's centre is thereby confined to within about R_pore − R of the axis.
// The beads' forces are reduced to each body's force and torque (system/rigid_sites.hpp).
#include <cstddef>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/integrate/body_forces.hpp"
#include "anisodyn/system/rigid_sites.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::lb {

struct PoreParameters {
  double radius = 0.0;              ///< R_pore: the hydrodynamic wall (σ)
  double wall_bead_radius = 6.25;   ///< r_p
  double bead_spacing = 5.0;        ///< centre to centre along z and around the rings
  double inner_bead_radius = 0.5;   ///< r_r of the raspberries' inner layer
  double epsilon = 1.0;             ///< WCA ε (k_BT)
};

class PoreWalls {
 public:
  /// The pore of a box (its axis along z at the centre of x and y); inner_sites[s]: the inner-layer
  /// offsets of species s (empty: no excluded volume).
  PoreWalls(const PoreParameters& params, const Box& box, SiteTable inner_sites);

  /// Adds the walls' force and torque on every body to out; returns the potential energy.
  double add(const State& state, BodyForces& out);

  /// Distance of a point from the pore axis.
  double radial_distance(const Vec3& r) const;
  std::size_t rings() const { return rings_; }
  std::size_t beads_per_ring() const { return per_ring_; }
  double ring_spacing() const { return dz_; }
  double sigma() const { return sigma_; }

 private:
  /// The WCA force on a bead at r from every wall bead within the cut-off; adds its energy.
  Vec3 bead_force(const Vec3& r, double& energy) const;

  PoreParameters params_;
  SiteTable inner_;
  std::vector<double> reach_;  ///< per species: the farthest inner bead from the centre
  Vec3 axis_;            ///< a point on the axis (x, y of the box centre)
  double length_;        ///< the box along z
  double wall_radius_;   ///< R_pore + r_p
  std::size_t rings_, per_ring_;
  double dz_, sigma_, cutoff_;
  std::vector<double> cos_, sin_;  ///< of each bead's angle on a ring
  std::vector<Vec3> bead_forces_;  ///< one body's beads, kept from call to call
};

}  // namespace anisodyn::lb
