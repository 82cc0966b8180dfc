// The "cell_centres" shell construction (shell_surface.hpp): one bead at the centre of each surface
// cell about 2σ_b across. It shares no placement rule with the default "surface_grid" (grid nodes,
// rings along meridians, beads on edges and rims), so agreement between the two after extrapolation
// to σ_b → 0 checks the extrapolated values rather than one discretisation.
//
// Every cell coordinate is written as (k + ½ − n/2)·step, which is exactly antisymmetric under
// k ↦ n − 1 − k, so the shells keep the mirror symmetry of the body bit for bit.
#include <cmath>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/shell_surface.hpp"

namespace anisodyn::hydro {

namespace {

/// Centre of cell k of n equal cells on [−extent/2, extent/2].
double cell_centre(int k, int n, double extent) { return (k + 0.5 - 0.5 * n) * (extent / n); }

/// Rectangular cells on the six faces; face normal along axis a, cells along the other two.
std::vector<Vec3> cuboid_cells(const Vec3& edges, double sigma_b) {
  Int3 n;
  for (int a = 0; a < 3; ++a) n[a] = bead_intervals(edges[a], sigma_b);
  std::vector<Vec3> beads;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (double side : {-0.5, 0.5})
      for (int i = 0; i < n[b]; ++i)
        for (int j = 0; j < n[c]; ++j) {
          Vec3 p;
          p[a] = side * edges[a];
          p[b] = cell_centre(i, n[b], edges[b]);
          p[c] = cell_centre(j, n[c], edges[c]);
          beads.push_back(p);
        }
  }
  return beads;
}

/// Point of the ellipsoid on the cubed-sphere face with normal ±axis a at angles (α along b, β
/// along c), each in [−π/4, π/4]: the unit direction (±1, tan α, tan β) scaled by the semi-axes.
Vec3 cubed_sphere_point(const Vec3& semi, int a, double side, double alpha, double beta) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  Vec3 d;
  d[a] = side;
  d[b] = std::tan(alpha);
  d[c] = std::tan(beta);
  return semi.cwiseProduct(d.normalized());
}

/// Length on the ellipsoid of the centre line of face a along direction b (α from −π/4 to π/4).
double face_centre_line_length(const Vec3& semi, int a, bool along_b) {
  constexpr int kSegments = 512;
  double length = 0.0;
  Vec3 previous = Vec3::Zero();
  for (int k = 0; k <= kSegments; ++k) {
    const double angle = -M_PI / 4 + (M_PI / 2) * k / kSegments;
    const Vec3 p = along_b ? cubed_sphere_point(semi, a, 1.0, angle, 0.0) : cubed_sphere_point(semi, a, 1.0, 0.0, angle);
    if (k > 0) length += (p - previous).norm();
    previous = p;
  }
  return length;
}

/// Equi-angular cubed sphere mapped onto the ellipsoid; each face gets its own cell counts from the
/// lengths of its centre lines, so elongated ellipsoids keep cells about 2σ_b across.
std::vector<Vec3> ellipsoid_cells(const Vec3& semi, double sigma_b) {
  std::vector<Vec3> beads;
  for (int a = 0; a < 3; ++a) {
    const int nb = bead_intervals(face_centre_line_length(semi, a, true), sigma_b);
    const int nc = bead_intervals(face_centre_line_length(semi, a, false), sigma_b);
    for (double side : {-1.0, 1.0})
      for (int i = 0; i < nb; ++i)
        for (int j = 0; j < nc; ++j)
          beads.push_back(cubed_sphere_point(semi, a, side, cell_centre(i, nb, M_PI / 2), cell_centre(j, nc, M_PI / 2)));
  }
  return beads;
}

/// Azimuths of n cells around a circle, n even so that both vertical mirror planes are kept.
int even_cell_count(double circumference, double sigma_b) { return 2 * bead_intervals(0.5 * circumference, sigma_b); }

void add_ring(std::vector<Vec3>& beads, double radius, double z, int n) {
  for (int j = 0; j < n; ++j) {
    const double phi = cell_centre(j, n, 2.0 * M_PI);
    beads.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
  }
}

/// Side: n_z × n_φ rectangles; each end disk: annuli of equal width cut into sectors.
std::vector<Vec3> cylinder_cells(double length, double d, double sigma_b) {
  const double R = 0.5 * d;
  std::vector<Vec3> beads;
  const int nz = bead_intervals(length, sigma_b), nphi = even_cell_count(2.0 * M_PI * R, sigma_b);
  for (int k = 0; k < nz; ++k) add_ring(beads, R, cell_centre(k, nz, length), nphi);
  const int nr = bead_intervals(R, sigma_b);
  for (double z : {-0.5 * length, 0.5 * length})
    for (int k = 0; k < nr; ++k) {
      const double r = (k + 0.5) * R / nr;
      add_ring(beads, r, z, even_cell_count(2.0 * M_PI * r, sigma_b));
    }
  return beads;
}

}  // namespace

std::vector<Vec3> cell_centre_beads(const HydroShape& s, double sigma_b) {
  if (!(sigma_b > 0.0)) throw InputError("bead radius must be positive");
  switch (s.kind) {
    case HydroShapeKind::Ellipsoid: return ellipsoid_cells(s.semi_axes, sigma_b);
    case HydroShapeKind::Cylinder: return cylinder_cells(s.length, s.diameter, sigma_b);
    case HydroShapeKind::Cuboid: return cuboid_cells(s.edges, sigma_b);
    case HydroShapeKind::Spherocylinder:
    case HydroShapeKind::SphereUnion: break;
  }
  throw InputError("the cell_centres shell construction covers spheres, ellipsoids, cubes, cuboids and cylinders only");
}

}  // namespace anisodyn::hydro
