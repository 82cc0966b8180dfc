#pragma once
// The convex bodies of the hydrodynamic validation for the walk-on-spheres capacitance solver
// (walk_on_spheres.hpp): cuboid, finite circular cylinder and ellipsoid, each centred with its
// axes along x, y, z. Each gives
//  - its exact distance from an outside point;
//  - a launch ellipsoid through its outermost points, chosen to have the least capacitance among
//    the ones scanned (the closer C_B is to C, the more walks hit);
//  - unit charges inside it whose potentials serve as control variates: mirror-symmetric point
//    charges and rings on a copy of its surface moved inwards by a fraction of its smallest
//    half-extent, about that depth apart (the source layout of the method of fundamental
//    solutions). Any layout keeps the estimate unbiased; a closer fit only lowers its variance
//    (for the cube, depth 0.3: SE ÷ 10 against plain walk on spheres; depth 0.2: ÷ 15).
#include <algorithm>
#include <cmath>
#include <vector>

#include "walk_on_spheres.hpp"

namespace anisodyn::testing_support {

// ---- distances -------------------------------------------------------------------------------------

class CuboidBody : public ConvexBody {
 public:
  explicit CuboidBody(const Vec3& edges) : half_(0.5 * edges) {}
  double distance(const Vec3& x) const override { return (x.cwiseAbs() - half_).cwiseMax(0.0).norm(); }
  double inradius() const override { return half_.minCoeff(); }
  double circumradius() const override { return half_.norm(); }
  const Vec3& half_extents() const { return half_; }

 private:
  Vec3 half_;
};

class CylinderBody : public ConvexBody {
 public:
  CylinderBody(double length, double diameter) : radius_(0.5 * diameter), half_length_(0.5 * length) {}
  double distance(const Vec3& x) const override {
    return std::hypot(std::max(std::hypot(x.x(), x.y()) - radius_, 0.0), std::max(std::abs(x.z()) - half_length_, 0.0));
  }
  double inradius() const override { return std::min(radius_, half_length_); }
  double circumradius() const override { return std::hypot(radius_, half_length_); }
  double radius() const { return radius_; }
  double half_length() const { return half_length_; }

 private:
  double radius_, half_length_;
};

/// Distance from y to the ellipsoid with semi-axes e (0 inside). The nearest point is
/// x_i = e_i² y_i/(t + e_i²), t the root of F(t) = Σ (e_i y_i/(t + e_i²))² − 1, which is convex and
/// decreasing for t > −min e²: Newton from a point left of the root converges monotonically.
/// t_0 = max(0, e_min|y| − e_max²) is left of it, since F(t_0) ≥ e_min²|y|²/(t_0 + e_max²)² − 1 ≥ 0.
inline double ellipsoid_distance(const Vec3& e, const Vec3& point) {
  const Vec3 y = point.cwiseAbs();
  if (y.cwiseQuotient(e).squaredNorm() <= 1.0) return 0.0;
  const Vec3 e2 = e.cwiseProduct(e);
  double t = std::max(0.0, e.minCoeff() * y.norm() - e2.maxCoeff());
  for (int it = 0; it < 200; ++it) {
    double F = -1.0, dF = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double w = e[i] * y[i] / (t + e2[i]);
      F += w * w;
      dF -= 2.0 * w * w / (t + e2[i]);
    }
    const double step = -F / dF;
    t += step;
    if (!(step > 1e-15 * (t + e2.maxCoeff()))) break;
  }
  Vec3 nearest;
  for (int i = 0; i < 3; ++i) nearest[i] = e2[i] * y[i] / (t + e2[i]);
  return (y - nearest).norm();
}

class EllipsoidBody : public ConvexBody {
 public:
  explicit EllipsoidBody(const Vec3& semi_axes) : semi_(semi_axes) {}
  double distance(const Vec3& x) const override { return ellipsoid_distance(semi_, x); }
  double inradius() const override { return semi_.minCoeff(); }
  double circumradius() const override { return semi_.maxCoeff(); }
  const Vec3& semi_axes() const { return semi_; }

 private:
  Vec3 semi_;
};

// ---- unit charges (control variates) ---------------------------------------------------------------

/// A unit charge shared equally by p and its distinct mirror images diag(±1, ±1, ±1)·p.
inline UnitChargePotential mirror_point_charges(const Vec3& p) {
  std::vector<Vec3> points;
  for (int mask = 0; mask < 8; ++mask) {
    const Vec3 q((mask & 1) ? -p.x() : p.x(), (mask & 2) ? -p.y() : p.y(), (mask & 4) ? -p.z() : p.z());
    if (std::none_of(points.begin(), points.end(), [&](const Vec3& o) { return (o - q).norm() < 1e-12; })) points.push_back(q);
  }
  return [points](const Vec3& x) {
    double g = 0.0;
    for (const Vec3& q : points) g += 1.0 / (x - q).norm();
    return g / static_cast<double>(points.size());
  };
}

/// A unit charge shared by the rings of radius a about the z axis at heights ±z (one ring if z = 0).
/// Ring potential (2/π) K(k)/√((ρ + a)² + Δz²), k² = 4aρ/((ρ + a)² + Δz²) (Smythe §5.08).
inline UnitChargePotential ring_charges(double a, double z) {
  auto ring = [a](double rho, double dz) {
    const double s2 = (rho + a) * (rho + a) + dz * dz;
    return (2.0 / M_PI) * std::comp_ellint_1(std::sqrt(4.0 * a * rho / s2)) / std::sqrt(s2);
  };
  return [ring, z](const Vec3& x) {
    const double rho = std::hypot(x.x(), x.y());
    return z == 0.0 ? ring(rho, x.z()) : 0.5 * (ring(rho, x.z() - z) + ring(rho, x.z() + z));
  };
}

namespace bodies_detail {

/// Sources sit at this fraction of the smallest half-extent below the surface by default.
constexpr double kSourceDepth = 0.3;
constexpr int kMaxSourceIntervals = 12;

/// Grid intervals for a length, at about the source depth apart.
inline int source_intervals(double length, double depth) {
  return std::clamp(static_cast<int>(std::lround(length / depth)), 1, kMaxSourceIntervals);
}

inline double grid(double extent, int k, int n) { return extent * k / n; }

}  // namespace bodies_detail

/// Mirror-symmetric point charges on the surface of the box of half-extents h − depth, plus the
/// centre; depth = depth_fraction × the smallest half-extent.
inline std::vector<UnitChargePotential> cuboid_charges(const CuboidBody& body,
                                                       double depth_fraction = bodies_detail::kSourceDepth) {
  using namespace bodies_detail;
  const double depth = depth_fraction * body.inradius();
  const Vec3 g = body.half_extents() - Vec3::Constant(depth);
  Int3 n;
  for (int a = 0; a < 3; ++a) n[a] = source_intervals(g[a], depth);
  std::vector<UnitChargePotential> out{mirror_point_charges(Vec3::Zero())};
  for (int i = 0; i <= n.x(); ++i)
    for (int j = 0; j <= n.y(); ++j)
      for (int k = 0; k <= n.z(); ++k)
        if (i == n.x() || j == n.y() || k == n.z())
          out.push_back(mirror_point_charges(Vec3(grid(g.x(), i, n.x()), grid(g.y(), j, n.y()), grid(g.z(), k, n.z()))));
  return out;
}

/// Rings and axis points on the cylinder moved inwards by `depth`: rings along the side, rings
/// filling the end disks, axis points at every level.
inline std::vector<UnitChargePotential> cylinder_charges(const CylinderBody& body) {
  using namespace bodies_detail;
  const double depth = kSourceDepth * body.inradius();
  const double a = body.radius() - depth, h = body.half_length() - depth;
  const int nz = source_intervals(h, depth), nr = source_intervals(a, depth);
  std::vector<UnitChargePotential> out;
  for (int k = 0; k <= nz; ++k) {
    out.push_back(mirror_point_charges(Vec3(0.0, 0.0, grid(h, k, nz))));
    out.push_back(ring_charges(a, grid(h, k, nz)));
  }
  for (int j = 1; j < nr; ++j) out.push_back(ring_charges(grid(a, j, nr), h));
  return out;
}

/// Spheroids (semi-axes c, c, a): the exterior potential is that of a line charge between the
/// foci (prolate) or of a charge on the focal disk (oblate); points or rings sample either.
inline std::vector<UnitChargePotential> spheroid_charges(const EllipsoidBody& body) {
  const double c = body.semi_axes().x(), a = body.semi_axes().z(), focal = std::sqrt(std::abs(a * a - c * c));
  constexpr int n = 8;
  std::vector<UnitChargePotential> out{mirror_point_charges(Vec3::Zero())};
  for (int k = 1; k <= n; ++k) {
    const double s = focal * k / (n + 1.0);
    out.push_back(a > c ? mirror_point_charges(Vec3(0.0, 0.0, s)) : ring_charges(s, 0.0));
  }
  return out;
}

// ---- launch ellipsoids -----------------------------------------------------------------------------

/// Semi-axes b_i = h_i/√w_i with Σ w_i = 1 pass through the corners (±h_x, ±h_y, ±h_z), so the
/// ellipsoid contains their convex hull. Scans the weights, coarse then fine, for the least
/// capacitance; equal_xy keeps w_x = w_y (b_x = b_y when h_x = h_y).
inline LaunchEllipsoid least_capacitance_launch(const Vec3& h, bool equal_xy) {
  auto semi = [&](double wx, double wy) { return Vec3(h.x() / std::sqrt(wx), h.y() / std::sqrt(wy), h.z() / std::sqrt(1.0 - wx - wy)); };
  auto capacitance = [&](double wx, double wy) {
    const Vec3 b = semi(wx, wy);
    return theory::ellipsoid_capacitance(b.x(), b.y(), b.z());
  };
  double best_x = 1.0 / 3.0, best_y = 1.0 / 3.0, best = capacitance(best_x, best_y);
  for (double step : {0.05, 0.01, 0.002}) {
    const double cx = best_x, cy = best_y;
    for (int i = -5; i <= 5; ++i)
      for (int j = -5; j <= 5; ++j) {
        const double wx = cx + i * step, wy = equal_xy ? wx : cy + j * step;
        if (wx <= 0.0 || wy <= 0.0 || wx + wy >= 1.0 || (equal_xy && j != 0)) continue;
        const double C = capacitance(wx, wy);
        if (C < best) best = C, best_x = wx, best_y = wy;
      }
  }
  return LaunchEllipsoid(semi(best_x, best_y));
}

inline LaunchEllipsoid launch_for(const CuboidBody& body) {
  const Vec3 h = body.half_extents();
  return least_capacitance_launch(h, h.x() == h.y());
}

/// Through the rim circles (ρ = R, z = ±h): b_x = b_y.
inline LaunchEllipsoid launch_for(const CylinderBody& body) {
  const double r = body.radius() / std::sqrt(2.0);  // a box corner (r, r, h) lies on the rim
  return least_capacitance_launch(Vec3(r, r, body.half_length()), true);
}

}  // namespace anisodyn::testing_support
