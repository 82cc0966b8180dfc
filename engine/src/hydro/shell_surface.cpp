#include "anisodyn/hydro/shell_surface.hpp"

#include <cmath>
#include <functional>

#include "anisodyn/core/error.hpp"

namespace anisodyn::hydro {

namespace {

using Vec2 = Eigen::Vector2d;  // (ρ, z) on a meridian, or (x, y) on a ring
using Curve = std::function<Vec2(double)>;

constexpr int kArcSamples = 4096;

/// Parameters t_0 = t0 < t_1 < … < t_n = t1 that split the curve into n arcs of equal length
/// (cumulative length tabulated on a fine grid and inverted by linear interpolation).
std::vector<double> equal_arc_parameters(const Curve& curve, double t0, double t1, int n) {
  std::vector<double> t(kArcSamples + 1), s(kArcSamples + 1, 0.0);
  for (int k = 0; k <= kArcSamples; ++k) t[k] = t0 + (t1 - t0) * k / kArcSamples;
  for (int k = 1; k <= kArcSamples; ++k) s[k] = s[k - 1] + (curve(t[k]) - curve(t[k - 1])).norm();
  std::vector<double> out{t0};
  int k = 0;
  for (int i = 1; i < n; ++i) {
    const double target = s.back() * i / n;
    while (s[k + 1] < target) ++k;
    const double f = (target - s[k]) / (s[k + 1] - s[k]);
    out.push_back(t[k] + f * (t[k + 1] - t[k]));
  }
  out.push_back(t1);
  return out;
}

double curve_length(const Curve& curve, double t0, double t1) {
  double s = 0.0;
  for (int k = 1; k <= kArcSamples; ++k)
    s += (curve(t0 + (t1 - t0) * k / kArcSamples) - curve(t0 + (t1 - t0) * (k - 1) / kArcSamples)).norm();
  return s;
}

/// One piece of a meridian, as a curve t ↦ (ρ, z) over [t0, t1].
struct MeridianSegment {
  Curve curve;
  double t0, t1;
};

/// A surface of revolution about z (ring cross-sections are ellipses with y/x semi-axis ratio
/// `y_ratio`, 1 for bodies of revolution), covered ring by ring.
std::vector<Vec3> revolution_shell(const std::vector<MeridianSegment>& meridian, double y_ratio, double sigma_b) {
  std::vector<Vec2> ring_points;
  for (std::size_t k = 0; k < meridian.size(); ++k) {
    const auto& seg = meridian[k];
    const int m = bead_intervals(curve_length(seg.curve, seg.t0, seg.t1), sigma_b);
    const auto t = equal_arc_parameters(seg.curve, seg.t0, seg.t1, m);
    for (std::size_t i = (k == 0 ? 0 : 1); i < t.size(); ++i) ring_points.push_back(seg.curve(t[i]));
  }
  const double scale = std::max(std::abs(ring_points.front().y()), std::abs(ring_points.back().y())) + sigma_b;
  std::vector<Vec3> beads;
  for (std::size_t k = 0; k < ring_points.size(); ++k) {
    const double rho = ring_points[k].x(), z = ring_points[k].y();
    if (rho < 1e-12 * scale) {  // a pole or the centre of an end disk
      beads.emplace_back(0.0, 0.0, z);
      continue;
    }
    const Curve ring = [&](double phi) { return Vec2(rho * std::cos(phi), y_ratio * rho * std::sin(phi)); };
    // An even count keeps both vertical mirror planes; staggering alternate rings by half a step
    // packs the beads more evenly.
    const int n = 2 * std::max(1, static_cast<int>(std::lround(curve_length(ring, 0.0, 2.0 * M_PI) / (4.0 * sigma_b))));
    const auto phi = equal_arc_parameters(ring, 0.0, 2.0 * M_PI, 2 * n);
    // Parity counted from the nearer end of the meridian, so the staggering is mirror-symmetric in z.
    const std::size_t stagger = std::min(k, ring_points.size() - 1 - k) % 2;
    for (int i = 0; i < n; ++i) {
      const Vec2 p = ring(phi[static_cast<std::size_t>(2 * i) + stagger]);
      beads.emplace_back(p.x(), p.y(), z);
    }
  }
  return beads;
}

std::vector<Vec3> ellipsoid_shell(const Vec3& a, double sigma_b) {
  // Meridian in the xz-plane from the south pole to the north pole.
  const Curve meridian = [a](double t) { return Vec2(a.x() * std::sin(t), -a.z() * std::cos(t)); };
  return revolution_shell({{meridian, 0.0, M_PI}}, a.y() / a.x(), sigma_b);
}

std::vector<Vec3> cylinder_shell(double length, double d, double sigma_b) {
  const double R = 0.5 * d, h = 0.5 * length;
  return revolution_shell({{[h](double t) { return Vec2(t, -h); }, 0.0, R},
                           {[R](double t) { return Vec2(R, t); }, -h, h},
                           {[R, h](double t) { return Vec2(R - t, h); }, 0.0, R}},
                          1.0, sigma_b);
}

std::vector<Vec3> spherocylinder_shell(double length, double d, double sigma_b) {
  const double R = 0.5 * d, h = 0.5 * length;
  std::vector<MeridianSegment> m{{[R, h](double t) { return Vec2(R * std::sin(t), -h - R * std::cos(t)); }, 0.0, M_PI / 2}};
  if (length > 0.0) m.push_back({[R](double t) { return Vec2(R, t); }, -h, h});
  m.push_back({[R, h](double t) { return Vec2(R * std::cos(t), h + R * std::sin(t)); }, 0.0, M_PI / 2});
  return revolution_shell(m, 1.0, sigma_b);
}

std::vector<Vec3> cuboid_shell(const Vec3& edges, double sigma_b) {
  Int3 n;
  for (int a = 0; a < 3; ++a) n[a] = bead_intervals(edges[a], sigma_b);
  const Vec3 h = edges.cwiseQuotient(n.cast<double>());
  std::vector<Vec3> beads;
  for (int i = 0; i <= n.x(); ++i)
    for (int j = 0; j <= n.y(); ++j)
      for (int k = 0; k <= n.z(); ++k) {
        const bool on_face = i == 0 || i == n.x() || j == 0 || j == n.y() || k == 0 || k == n.z();
        // (i − n/2)·h is exact in its half-integer factor, so mirror images are bit-identical.
        if (on_face) beads.emplace_back((i - 0.5 * n.x()) * h.x(), (j - 0.5 * n.y()) * h.y(), (k - 0.5 * n.z()) * h.z());
      }
  return beads;
}

std::vector<Vec3> sphere_union_shell(const HydroShape& s, double sigma_b) {
  std::vector<Vec3> beads;
  for (std::size_t k = 0; k < s.sphere_centres.size(); ++k) {
    for (const Vec3& p : ellipsoid_shell(Vec3::Constant(s.sphere_radii[k]), sigma_b)) {
      const Vec3 q = p + s.sphere_centres[k];
      bool exposed = true;
      for (std::size_t l = 0; l < s.sphere_centres.size() && exposed; ++l)
        if (l != k) exposed = (q - s.sphere_centres[l]).norm() >= s.sphere_radii[l] * (1.0 - 1e-9);
      // Beads on an intersection circle come from both spheres: keep one.
      for (std::size_t b = 0; b < beads.size() && exposed; ++b) exposed = (beads[b] - q).norm() > 0.2 * sigma_b;
      if (exposed) beads.push_back(q);
    }
  }
  return beads;
}

}  // namespace

int bead_intervals(double length, double sigma_b) {
  return std::max(1, static_cast<int>(std::lround(length / (2.0 * sigma_b))));
}

std::vector<Vec3> shell_beads(const HydroShape& s, double sigma_b) {
  if (!(sigma_b > 0.0)) throw InputError("bead radius must be positive");
  switch (s.kind) {
    case HydroShapeKind::Ellipsoid: return ellipsoid_shell(s.semi_axes, sigma_b);
    case HydroShapeKind::Cylinder: return cylinder_shell(s.length, s.diameter, sigma_b);
    case HydroShapeKind::Spherocylinder: return spherocylinder_shell(s.length, s.diameter, sigma_b);
    case HydroShapeKind::Cuboid: return cuboid_shell(s.edges, sigma_b);
    case HydroShapeKind::SphereUnion: return sphere_union_shell(s, sigma_b);
  }
  return {};
}

double thinnest_dimension(const HydroShape& s) {
  switch (s.kind) {
    case HydroShapeKind::Ellipsoid: return 2.0 * s.semi_axes.minCoeff();
    case HydroShapeKind::Cylinder: return std::min(s.length, s.diameter);
    case HydroShapeKind::Spherocylinder: return s.diameter;
    case HydroShapeKind::Cuboid: return s.edges.minCoeff();
    case HydroShapeKind::SphereUnion: {
      double r = s.sphere_radii.front();
      for (double x : s.sphere_radii) r = std::min(r, x);
      return 2.0 * r;
    }
  }
  return 0.0;
}

bool on_surface(const HydroShape& s, const Vec3& p, double tol) {
  switch (s.kind) {
    case HydroShapeKind::Ellipsoid: return std::abs(std::sqrt(p.cwiseQuotient(s.semi_axes).squaredNorm()) - 1.0) < tol;
    case HydroShapeKind::Cylinder: {
      const double R = 0.5 * s.diameter, h = 0.5 * s.length, rho = std::hypot(p.x(), p.y());
      const bool side = std::abs(rho - R) < tol && std::abs(p.z()) <= h + tol;
      const bool cap = std::abs(std::abs(p.z()) - h) < tol && rho <= R + tol;
      return side || cap;
    }
    case HydroShapeKind::Spherocylinder: {
      const double h = 0.5 * s.length;
      const Vec3 axis_point(0.0, 0.0, std::clamp(p.z(), -h, h));
      return std::abs((p - axis_point).norm() - 0.5 * s.diameter) < tol;
    }
    case HydroShapeKind::Cuboid: {
      const Vec3 q = p.cwiseAbs() - 0.5 * s.edges;
      return q.maxCoeff() < tol && q.maxCoeff() > -tol;
    }
    case HydroShapeKind::SphereUnion: {
      bool on_some = false;
      for (std::size_t k = 0; k < s.sphere_centres.size(); ++k) {
        const double d = (p - s.sphere_centres[k]).norm() - s.sphere_radii[k];
        if (d < -tol) return false;
        on_some = on_some || std::abs(d) < tol;
      }
      return on_some;
    }
  }
  return false;
}

}  // namespace anisodyn::hydro
