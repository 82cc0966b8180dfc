#include "anisodyn/lb/raspberry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "anisodyn/core/error.hpp"

namespace anisodyn::lb {

double spheroid_area(double a, double c) {
  if (a == c) return 4.0 * M_PI * a * a;
  if (a > c) {  // prolate
    const double e = std::sqrt(1.0 - c * c / (a * a));
    return 2.0 * M_PI * c * c * (1.0 + a / (c * e) * std::asin(e));
  }
  const double e = std::sqrt(1.0 - a * a / (c * c));  // oblate
  return 2.0 * M_PI * c * c * (1.0 + (1.0 - e * e) / e * std::atanh(e));
}

Vec3 nearest_surface_point(const Vec3& s, const Vec3& r) {
  const Vec3 s2 = s.cwiseProduct(s);
  const auto f = [&](double t) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) sum += std::pow(r[i] * s[i] / (t + s2[i]), 2);
    return sum - 1.0;
  };
  // F decreases on (−min s², ∞); F(max s · |r|) ≤ 0.
  const double lowest = -s2.minCoeff();
  const double floor = lowest + std::abs(lowest) * 1e-15;
  if (!(f(floor) > 0.0)) {
    // r has no component along the shortest axis and lies inside the ellipse across it: the
    // nearest points lie on that axis's side (t = −min s²); the component along it closes |r_s|.
    const int k = static_cast<int>(std::min_element(s2.data(), s2.data() + 3) - s2.data());
    Vec3 p = Vec3::Zero();
    double rest = 1.0;
    for (int i = 0; i < 3; ++i)
      if (i != k) {
        p[i] = r[i] * s2[i] / (s2[i] - s2[k]);
        rest -= p[i] * p[i] / s2[i];
      }
    p[k] = (r[k] < 0.0 ? -1.0 : 1.0) * s[k] * std::sqrt(std::max(rest, 0.0));
    return p;
  }
  double lo = floor, hi = s.maxCoeff() * r.norm();
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++iteration) {
    const double mid = 0.5 * (lo + hi);
    if (f(mid) > 0.0) lo = mid;
    else hi = mid;
  }
  const double t = 0.5 * (lo + hi);
  Vec3 p;
  for (int i = 0; i < 3; ++i) p[i] = r[i] * s2[i] / (t + s2[i]);
  return p;
}

LayerRelaxation sphere_layer_relaxation() { return LayerRelaxation{1.0, 1.0, 5000, 1e-3}; }
LayerRelaxation spheroid_layer_relaxation() { return LayerRelaxation{1.4, 0.1, 5000, 1e-3}; }

namespace {

/// The pair repulsion of a layer's beads, each bead's force with its component along the surface
/// normal removed (the surface constraint takes that part); returns the largest remaining force.
double tangential_forces(const Vec3& semi_axes, const LayerRelaxation& p, const std::vector<Vec3>& r, std::vector<Vec3>& force) {
  const std::size_t n = r.size();
  const double cut2 = std::pow(2.0, 1.0 / 3.0) * p.sigma * p.sigma, sigma2 = p.sigma * p.sigma;
  std::fill(force.begin(), force.end(), Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec3 d = r[i] - r[j];
      const double d2 = d.squaredNorm();
      if (d2 >= cut2) continue;
      const double s6 = std::pow(sigma2 / d2, 3);
      const Vec3 f = (24.0 * p.epsilon * (2.0 * s6 * s6 - s6) / d2) * d;
      force[i] += f;
      force[j] -= f;
    }
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 normal = r[k].cwiseQuotient(semi_axes.cwiseProduct(semi_axes)).normalized();  // ∇S at a surface point
    force[k] -= force[k].dot(normal) * normal;
    largest = std::max(largest, force[k].norm());
  }
  return largest;
}

}  // namespace

std::vector<Vec3> surface_layer(const Vec3& semi_axes, std::size_t count, const LayerRelaxation& p) {
  std::vector<Vec3> r(count), force(count);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t k = 0; k < count; ++k) {
    // The spiral's pole is body x, the symmetry axis.
    const double x = 1.0 - (2.0 * static_cast<double>(k) + 1.0) / static_cast<double>(count);
    const double rho = std::sqrt(std::max(0.0, 1.0 - x * x)), phi = golden * static_cast<double>(k);
    const Vec3 u(x, rho * std::cos(phi), rho * std::sin(phi));
    r[k] = u / std::sqrt(u.cwiseQuotient(semi_axes).squaredNorm());
  }
  // Projected descent: the spring to the nearest surface point taken infinitely stiff, so the
  // beads end on the design surface (with the spec's k_s = 100 the repulsion at 1 bead/nm² held
  // spheroid beads 0.5 nm off it); each bead moves along its tangential force, at most 0.02 nm per
  // iteration, and back onto the surface.
  const double step = 0.002 / p.epsilon, largest_move = 0.02;
  for (int iteration = 0; iteration < p.max_iterations; ++iteration) {
    if (tangential_forces(semi_axes, p, r, force) < p.force_tolerance * p.epsilon) break;
    for (std::size_t k = 0; k < count; ++k) {
      Vec3 move = step * force[k];
      const double length = move.norm();
      if (length > largest_move) move *= largest_move / length;
      r[k] = nearest_surface_point(semi_axes, r[k] + move);
    }
  }
  return r;
}

std::size_t RaspberryGeometry::count(BeadLayer which) const { return static_cast<std::size_t>(std::count(layer.begin(), layer.end(), which)); }

RaspberryGeometry make_raspberry(const Vec3& semi_axes, bool outer_layer) {
  const Vec3 inner = semi_axes - Vec3::Constant(0.5), fill = semi_axes - Vec3::Constant(1.0);
  if (!(inner.minCoeff() > 0.0))
    throw InputError("make_raspberry: the design surface needs semi-axes above 0.5 nm (the inner layer lies 0.5 nm inside it)");
  if (std::abs(semi_axes.y() - semi_axes.z()) > 1e-12 * semi_axes.y())
    throw InputError("make_raspberry: spheres and spheroids only (b = c across the symmetry axis a along body x)");
  RaspberryGeometry g;
  g.semi_axes = semi_axes;
  const bool sphere = std::abs(semi_axes.x() - semi_axes.y()) <= 1e-12 * semi_axes.y();
  const LayerRelaxation relaxation = sphere ? sphere_layer_relaxation() : spheroid_layer_relaxation();
  const auto add_layer = [&](const Vec3& axes, BeadLayer tag) {
    const auto n = static_cast<std::size_t>(std::lround(spheroid_area(axes.x(), axes.y())));
    for (const Vec3& r : surface_layer(axes, n, relaxation)) {
      g.offset.push_back(r);
      g.layer.push_back(tag);
    }
  };
  if (outer_layer) add_layer(semi_axes, BeadLayer::kOuter);
  add_layer(inner, BeadLayer::kInner);
  if (fill.minCoeff() > 0.0) {
    const Vec3 reach = fill.array().floor();
    for (double x = -reach.x(); x <= reach.x(); x += 1.0)
      for (double y = -reach.y(); y <= reach.y(); y += 1.0)
        for (double z = -reach.z(); z <= reach.z(); z += 1.0) {
          const Vec3 p(x, y, z);
          if (p == Vec3::Zero() || p.cwiseQuotient(fill).squaredNorm() > 1.0) continue;  // the centre bead comes next
          g.offset.push_back(p);
          g.layer.push_back(BeadLayer::kFill);
        }
  }
  g.offset.push_back(Vec3::Zero());
  g.layer.push_back(BeadLayer::kCentre);
  // The reference bead: the outermost layer's bead nearest 45° from the symmetry axis (a direction
  // that sees rotations about every axis).
  const BeadLayer surface = outer_layer ? BeadLayer::kOuter : BeadLayer::kInner;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < g.offset.size(); ++k) {
    if (g.layer[k] != surface) continue;
    const double alpha = std::acos(std::clamp(g.offset[k].x() / g.offset[k].norm(), -1.0, 1.0));
    if (std::abs(alpha - M_PI / 4) < best) {
      best = std::abs(alpha - M_PI / 4);
      g.reference_bead = k;
      g.reference_angle = alpha;
    }
  }
  return g;
}

double raspberry_mass(const Vec3& s, double fluid_density) { return fluid_density * 4.0 / 3.0 * M_PI * s.x() * s.y() * s.z(); }

Vec3 raspberry_moments(const Vec3& s, double mass) {
  const Vec3 s2 = s.cwiseProduct(s);
  return mass / 5.0 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
}

}  // namespace anisodyn::lb
