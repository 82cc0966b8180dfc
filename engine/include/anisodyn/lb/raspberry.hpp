#pragma once
// Raspberry bodies of spec 40 §4–5: the bead layers of a sphere or spheroid, in the body frame
// (symmetry semi-axis a along body x, b and c along y and z; lengths in nm = lattice units):
// - the outer layer on the design surface (hydrodynamic coupling only) and the inner layer on the
//   surface with semi-axes less ½ (coupling and excluded volume), each at 1 bead/nm²:
//   N = round(area), placed on a Fibonacci spiral mapped to the surface and relaxed on it under a
//   short-ranged repulsion between the layer's beads (§5.2; the allowed faster equivalent);
// - the filled interior: a simple-cubic grid of spacing 1 inside the semi-axes less 1 (§5.1);
// - the centre bead at the origin;
// plus the density-matched mass and the uniform solid spheroid's principal moments (§4).
#include <cstddef>
#include <string>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::lb {

/// Surface area of the spheroid with semi-axis a along its symmetry axis and c = b across
/// (spec 40 §5.1: prolate, oblate, and 4πa² for a sphere).
double spheroid_area(double a, double c);

/// The point of the ellipsoid x²/a² + y²/b² + z²/c² = 1 nearest to r, by the normal condition
/// r − r_s ∥ ∇S(r_s): r_s,i = r_i s_i²/(t + s_i²), t the largest root of F(t) = Σ (r_i s_i/(t + s_i²))² − 1,
/// found by bisection to |F| < 10⁻¹² (spec 40 §5.2; the spec asks 10⁻⁶).
Vec3 nearest_surface_point(const Vec3& semi_axes, const Vec3& r);

/// The repulsion that spreads a layer's beads over its surface (spec 40 §5.2). The spec's spring
/// to the nearest surface point is taken infinitely stiff: beads stay on the surface.
struct LayerRelaxation {
  double sigma = 1.0;            ///< the pair repulsion's σ (Lennard-Jones cut at 2^{1/6} σ)
  double epsilon = 1.0;          ///< and its ε
  int max_iterations = 5000;     ///< of the projected descent
  double force_tolerance = 1e-3; ///< stop when every tangential force is below this times ε
};

/// The spec's repulsion for sphere layers (WCA, σ = 1, ε = 1) and for spheroid layers (LJ σ = 1.4,
/// ε = 0.1, repulsive part).
LayerRelaxation sphere_layer_relaxation();
LayerRelaxation spheroid_layer_relaxation();

/// count beads spread over the ellipsoid surface: a Fibonacci spiral of directions, each mapped to
/// the surface along its ray, then a descent along the tangential repulsion, kept on the surface.
std::vector<Vec3> surface_layer(const Vec3& semi_axes, std::size_t count, const LayerRelaxation& relaxation);

enum class BeadLayer { kOuter, kInner, kFill, kCentre };

struct RaspberryGeometry {
  Vec3 semi_axes;                 ///< the design surface's (a, b, c)
  std::vector<Vec3> offset;       ///< body-frame bead positions
  std::vector<BeadLayer> layer;   ///< one per bead
  std::size_t reference_bead = 0; ///< an outer bead (spec 40 §4: recorded with the centre)
  double reference_angle = 0.0;   ///< its polar angle α from the symmetry axis (body x)

  std::size_t count(BeadLayer which) const;
};

/// The raspberry of a sphere (a = b = c = R) or spheroid (a, b = c): both layers at 1 bead/nm²,
/// the fill and the centre bead (spec 40 §5.1); without the outer layer when outer_layer is false
/// (spec 40 §6's single-layer ablation; the reference bead is then an inner one). Throws
/// InputError for an inner layer with a semi-axis ≤ 0 (a design surface thinner than 1 nm).
RaspberryGeometry make_raspberry(const Vec3& semi_axes, bool outer_layer = true);

/// m = ρ (4/3) π a b c: density matched to the fluid (spec 40 §4).
double raspberry_mass(const Vec3& semi_axes, double fluid_density);
/// The uniform solid ellipsoid's principal moments m (b² + c²)/5, m (a² + c²)/5, m (a² + b²)/5.
Vec3 raspberry_moments(const Vec3& semi_axes, double mass);

}  // namespace anisodyn::lb
