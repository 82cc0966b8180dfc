#include "anisodyn/dpd/colloid_bodies.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "anisodyn/core/error.hpp"

namespace anisodyn {

double ColloidBody::half_span() const {
  double r = 0.0;
  for (const Vec3& d : sites.offsets) r = std::max(r, d.norm());
  return r;
}

namespace {

ColloidBody sphere_body(double d, double density, bool rotating) {
  ColloidBody b;
  b.sites.offsets = {Vec3::Zero()};
  b.sites.radii = {d};
  b.volume = std::numbers::pi * d * d * d / 6.0;
  b.mass = density * b.volume;
  if (rotating) {
    b.moments = Vec3::Constant(b.mass * d * d / 10.0);  // solid sphere: (2/5) m (d/2)²
    b.rotational_degrees = 3;
  }
  return b;
}

ColloidBody rod_body(double cylinder, double d, double density, double spacing) {
  const double intervals = cylinder / spacing;
  const long n_intervals = std::lround(intervals);
  if (std::abs(intervals - static_cast<double>(n_intervals)) > 1e-9 * std::max(1.0, intervals))
    throw InputError("a rod's length minus its diameter (" + std::to_string(cylinder) + ") must be a whole number of site spacings (" +
                     std::to_string(spacing) + ")");
  const std::size_t n = static_cast<std::size_t>(n_intervals) + 1;
  ColloidBody b;
  for (std::size_t k = 0; k < n; ++k) {
    // Symmetric about 0 to the last bit: site k and site n − 1 − k get opposite offsets.
    const double z = (static_cast<double>(k) - 0.5 * static_cast<double>(n - 1)) * spacing;
    b.sites.offsets.push_back(Vec3(0.0, 0.0, z));
    b.sites.radii.push_back(d);
  }
  b.volume = std::numbers::pi * d * d * (d + 1.5 * cylinder) / 6.0;
  b.mass = density * b.volume;
  if (n > 1) {
    b.moments = point_mass_moments(b.sites.offsets, b.mass / static_cast<double>(n));
    b.rotational_degrees = 2;
  }
  return b;
}

}  // namespace

ColloidBody colloid_body(const Shape& shape, double mass_density, double site_spacing, bool rotating) {
  if (!(mass_density > 0.0)) throw InputError("the colloids' mass density must be positive");
  if (!(site_spacing > 0.0)) throw InputError("the rods' site spacing must be positive");
  switch (shape.kind) {
    case ShapeKind::Sphere: return sphere_body(shape.diameter, mass_density, rotating);
    case ShapeKind::Spherocylinder: return rod_body(shape.length, shape.diameter, mass_density, site_spacing);
    default:
      throw InputError(std::string("a DPD colloid is a sphere or a spherocylinder (a rod of spheres), not a ") +
                       shape_kind_name(shape.kind));
  }
}

}  // namespace anisodyn
