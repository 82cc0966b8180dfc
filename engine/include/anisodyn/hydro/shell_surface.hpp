#pragma once
// Shell models: minibeads of radius σ_b covering the surface of a rigid body (body frame, centred).
//
// Surfaces of revolution about body z (sphere, spheroid and triaxial ellipsoid, cylinder,
// spherocylinder) are covered ring by ring: points at equal arc length ≈ 2σ_b along the meridian,
// each carrying a ring of beads at ≈ 2σ_b spacing, alternate rings staggered by half a step; sharp
// edges (cylinder rims) carry a ring. Cuboids use a square grid on each face, edges and corners
// included (spec 10 §8.4 step 1). A union of spheres (the overlapping-sphere rods of spec 30) is
// the union of the sphere shells minus the beads buried inside another sphere. Bead counts along
// each line are even where possible, so the model keeps the mirror symmetry of the body.
#include <string>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shape.hpp"

namespace anisodyn::hydro {

enum class HydroShapeKind { Ellipsoid, Cylinder, Spherocylinder, Cuboid, SphereUnion };

struct HydroShape {
  HydroShapeKind kind = HydroShapeKind::Ellipsoid;
  Vec3 semi_axes = Vec3::Ones();  // ellipsoid (a sphere has three equal semi-axes)
  Vec3 edges = Vec3::Ones();      // cuboid: full edges along body x, y, z
  double length = 0.0;            // cylinder: full length; spherocylinder: length of the cylindrical part
  double diameter = 0.0;          // cylinder, spherocylinder
  std::vector<Vec3> sphere_centres;  // sphere union
  std::vector<double> sphere_radii;

  static HydroShape sphere(double d) { return ellipsoid(Vec3::Constant(0.5 * d)); }
  static HydroShape ellipsoid(const Vec3& semi_axes) {
    HydroShape s; s.kind = HydroShapeKind::Ellipsoid; s.semi_axes = semi_axes; return s;
  }
  static HydroShape cylinder(double length, double d) {
    HydroShape s; s.kind = HydroShapeKind::Cylinder; s.length = length; s.diameter = d; return s;
  }
  static HydroShape spherocylinder(double length, double d) {
    HydroShape s; s.kind = HydroShapeKind::Spherocylinder; s.length = length; s.diameter = d; return s;
  }
  static HydroShape cuboid(const Vec3& edges) {
    HydroShape s; s.kind = HydroShapeKind::Cuboid; s.edges = edges; return s;
  }
  static HydroShape sphere_union(std::vector<Vec3> centres, std::vector<double> radii) {
    HydroShape s; s.kind = HydroShapeKind::SphereUnion; s.sphere_centres = std::move(centres);
    s.sphere_radii = std::move(radii); return s;
  }
};


/// Bead centres of the shell at bead radius sigma_b (the default construction, "surface_grid").
std::vector<Vec3> shell_beads(const HydroShape& shape, double sigma_b);

/// A way of laying beads on a surface: the bead centres of the shell at bead radius σ_b.
using ShellConstruction = std::vector<Vec3> (*)(const HydroShape& shape, double sigma_b);

/// The second construction, "cell_centres" (cell_centre_shell.cpp), an independent check on the
/// first: the surface is cut into cells about 2σ_b across and one bead sits at the centre of each,
/// so no bead lies on an edge or a rim. Cuboid faces are cut into rectangles; ellipsoids into the
/// six faces of an equi-angular cubed sphere, mapped onto the ellipsoid; cylinders into rectangles on
/// the side and annular sectors on the end disks. Other shapes: InputError.
std::vector<Vec3> cell_centre_beads(const HydroShape& shape, double sigma_b);

/// Number of intervals of about 2σ_b that fit a length (at least one).
int bead_intervals(double length, double sigma_b);

/// The smallest body dimension (thickness): bead sizes are quoted relative to it.
double thinnest_dimension(const HydroShape& shape);

/// Signed distance-like test used by tests: the bead centre lies on the surface within `tol`.
bool on_surface(const HydroShape& shape, const Vec3& p, double tol);

}  // namespace anisodyn::hydro
