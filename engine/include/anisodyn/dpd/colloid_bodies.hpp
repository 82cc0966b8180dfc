#pragma once
// The rigid colloids of a DPD run (spec 30 §3): what a species' shape becomes as a body of sites.
//
//   sphere of diameter d        one site at the centre; a point mass ρ π d³/6 that does not rotate
//                               (the paper's "mass point", §3.1); with `rotating`, a solid sphere
//                               of that mass (moments m d²/10) that turns under the torques of
//                               the surface-velocity friction (interactions/site_liquid.hpp);
//   spherocylinder (ℓ, d)       total length L = ℓ + d: N_s = ℓ/Δl + 1 sites of diameter d spaced Δl
//                               on the axis (body z), centred on the centre of mass; each of mass
//                               ρ V / N_s with V = π d² (d + 1.5 ℓ)/6 the spherocylinder's volume;
//                               a linear rotor (moments I⊥, I⊥, 0) (§3.2).
//
// ρ is the colloid's mass density (density matched: the liquid's, 3 m/r_c³). Any other shape, or a
// rod whose ℓ is not a whole number of spacings, is an InputError.
#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/system/rigid_sites.hpp"

namespace anisodyn {

struct ColloidBody {
  SiteBody sites;         // offsets in the body frame; radii hold the site diameters
  double mass = 0.0;      // the whole body
  Vec3 moments = Vec3::Zero();  // principal moments about body x, y, z (a sphere: none)
  double volume = 0.0;    // the core's volume
  int rotational_degrees = 0;   // 0 (sphere), 3 (rotating sphere), 2 (rod)

  /// The largest distance of a site centre from the body centre.
  double half_span() const;
  /// The body's extent along its axis with every site's reach r around it: 2 (half_span + r).
  double extent(double reach) const { return 2.0 * (half_span() + reach); }
};

/// `rotating`: spheres get their moments of inertia (rods are linear rotors either way).
ColloidBody colloid_body(const Shape& shape, double mass_density, double site_spacing, bool rotating = false);

}  // namespace anisodyn
