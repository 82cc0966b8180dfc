#include "anisodyn/analysis/raspberry_diffusion.hpp"

#include <algorithm>
#include <cmath>

#include "anisodyn/analysis/body_frame_increments.hpp"

namespace anisodyn::analysis {

namespace {

/// ⟨arccos(u(t)·u(t + k))²⟩ for k = 1 … max_lag, of unit vectors u.
std::vector<double> angle_mean_squares(std::span<const Vec3> u, std::size_t max_lag) {
  std::vector<double> out(max_lag, 0.0);
  for (std::size_t k = 1; k <= max_lag; ++k) {
    double sum = 0.0;
    for (std::size_t t = 0; t + k < u.size(); ++t) {
      const double angle = std::acos(std::clamp(u[t].dot(u[t + k]), -1.0, 1.0));
      sum += angle * angle;
    }
    out[k - 1] = sum / static_cast<double>(u.size() - k);
  }
  return out;
}

}  // namespace

std::vector<Vec3> component_mean_squares(std::span<const Vec3> path, std::size_t max_lag) {
  std::vector<Vec3> out(max_lag, Vec3::Zero());
  for (std::size_t k = 1; k <= max_lag; ++k) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t t = 0; t + k < path.size(); ++t) sum += (path[t + k] - path[t]).cwiseAbs2();
    out[k - 1] = sum / static_cast<double>(path.size() - k);
  }
  return out;
}

BodyLagCurves body_lag_curves(std::span<const Vec3> centre, std::span<const Quat> orientation, const Vec3& reference, std::size_t max_lag) {
  BodyLagCurves c;
  for (const Vec3& m : component_mean_squares(centre, max_lag)) c.lab.push_back(m.sum());
  std::vector<Vec3> vector(orientation.size());
  std::array<std::vector<Vec3>, 3> axes;
  for (std::size_t f = 0; f < orientation.size(); ++f) {
    const Mat3 rot = orientation[f].toRotationMatrix();
    vector[f] = (rot * reference).normalized();
    for (std::size_t i = 0; i < 3; ++i) axes[i].push_back(rot.col(static_cast<int>(i)));
  }
  c.vector_angle = angle_mean_squares(vector, max_lag);
  c.axes_angle.assign(max_lag, 0.0);
  for (const auto& axis : axes) {
    const auto m = angle_mean_squares(axis, max_lag);
    for (std::size_t k = 0; k < max_lag; ++k) c.axes_angle[k] += m[k];
  }
  const auto translation = component_mean_squares(accumulate_path(body_frame_displacements(centre, orientation)), max_lag);
  const auto rotation = component_mean_squares(accumulate_path(body_frame_rotation_angles(orientation)), max_lag);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < max_lag; ++k) {
      c.body_translation[i].push_back(translation[k][static_cast<int>(i)]);
      c.body_rotation[i].push_back(rotation[k][static_cast<int>(i)]);
    }
  return c;
}

std::vector<double> BodyLagCurves::flatten() const {
  std::vector<double> out;
  for (const auto* curve : {&lab, &vector_angle, &axes_angle, &body_translation[0], &body_translation[1], &body_translation[2], &body_rotation[0],
                            &body_rotation[1], &body_rotation[2]})
    out.insert(out.end(), curve->begin(), curve->end());
  return out;
}

BodyLagCurves BodyLagCurves::unflatten(const std::vector<double>& flat) {
  BodyLagCurves c;
  const std::size_t k = flat.size() / kCurves;
  std::size_t at = 0;
  for (auto* curve : {&c.lab, &c.vector_angle, &c.axes_angle, &c.body_translation[0], &c.body_translation[1], &c.body_translation[2], &c.body_rotation[0],
                      &c.body_rotation[1], &c.body_rotation[2]}) {
    curve->assign(flat.begin() + static_cast<std::ptrdiff_t>(at), flat.begin() + static_cast<std::ptrdiff_t>(at + k));
    at += k;
  }
  return c;
}

}  // namespace anisodyn::analysis
