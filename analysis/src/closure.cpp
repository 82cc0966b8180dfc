#include "anisodyn/analysis/closure.hpp"

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

Mat3 fourth_moment_contraction(const std::vector<Vec3>& axes, const Mat3& order) {
  Mat3 out = Mat3::Zero();
  for (const Vec3& u : axes) out += (u.dot(order * u)) * (u * u.transpose());
  return axes.empty() ? out : Mat3(out / static_cast<double>(axes.size()));
}

Mat3 closure_approximation(const Mat3& order) {
  const double s_s = (order.array() * order.array()).sum();  // S:S
  return (2.0 * order * order + 3.0 * s_s * order) / 5.0;
}

ClosureSides closure_sides(const std::vector<Vec3>& axes) {
  ClosureSides c;
  for (const Vec3& u : axes) c.order += u * u.transpose();
  if (!axes.empty()) c.order /= static_cast<double>(axes.size());
  c.exact = fourth_moment_contraction(axes, c.order);
  c.closure = closure_approximation(c.order);
  return c;
}

const std::vector<std::string>& closure_series_names() {
  static const std::vector<std::string> names{"S_xx", "S_yy", "S_zz", "S4S_xx", "S4S_yy", "S4S_zz", "closure_xx", "closure_yy", "closure_zz"};
  return names;
}

ClosureAnalysis::ClosureAnalysis(int rod_axis) : rod_axis_(rod_axis) {}

void ClosureAnalysis::accumulate(const Trajectory& t, int species_index) {
  const auto members = t.members(species_index);
  if (members.empty()) throw InputError(t.path, "/particles/all/species", "no particle of the selected species");
  rods_ = members.size();
  std::vector<std::vector<double>> v(closure_series_names().size(), std::vector<double>(t.frames));
  for (std::size_t f = 0; f < t.frames; ++f) {
    std::vector<Vec3> axes;
    for (const Mat3& r : frame_rotations(t, f, members)) axes.push_back(r.col(rod_axis_));
    const ClosureSides c = closure_sides(axes);
    for (int d = 0; d < 3; ++d) {
      v[static_cast<std::size_t>(d)][f] = c.order(d, d);
      v[static_cast<std::size_t>(3 + d)][f] = c.exact(d, d);
      v[static_cast<std::size_t>(6 + d)][f] = c.closure(d, d);
    }
  }
  times_.push_back(t.time);
  values_.push_back(std::move(v));
}

ClosureResult ClosureAnalysis::compute(const std::vector<double>& common_time) const {
  ClosureResult r;
  r.time = common_time;
  r.replicas = times_.size();
  r.rods = rods_;
  const auto& names = closure_series_names();
  for (std::size_t k = 0; k < names.size(); ++k) {
    CurveSamples curves;
    for (std::size_t rep = 0; rep < times_.size(); ++rep) curves.add(interpolate_onto(times_[rep], values_[rep][k], common_time));
    r.series.push_back({names[k], curves.mean(), curves.standard_error()});
  }
  return r;
}

}  // namespace anisodyn::analysis
