#include "anisodyn/analysis/torque_drag.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "anisodyn/analysis/bd_caps.hpp"
#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

namespace {
constexpr std::size_t kBlocks = 10;
const std::string kConfigPath = "/parameters/config";

/// ê₁, ê₂ with (ê₁, ê₂, ê) right-handed: a positive torque along ê turns θ forwards.
std::pair<Vec3, Vec3> in_plane_basis(const Vec3& e) {
  const Vec3 helper = std::abs(e.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = (helper - helper.dot(e) * e).normalized();
  return {e1, e.cross(e1)};
}

double slope(const std::vector<double>& t, const std::vector<double>& theta, std::size_t first, std::size_t last) {
  return fit_line(std::vector<double>(t.begin() + static_cast<std::ptrdiff_t>(first), t.begin() + static_cast<std::ptrdiff_t>(last)),
                  std::vector<double>(theta.begin() + static_cast<std::ptrdiff_t>(first), theta.begin() + static_cast<std::ptrdiff_t>(last)))
      .slope;
}
}  // namespace

ExternalTorqueRun external_torque_of(const Trajectory& t) {
  tool::ConfigNode run(t.parameters.is_object() ? t.parameters : nlohmann::json::object(), t.path, kConfigPath);
  if (!run.has("external_torque"))
    throw InputError(t.path, kConfigPath + ": external_torque",
                     "expected a run with an external torque (anisodyn-bd's external_torque, spec 20 §6.2 Method II)");
  tool::ConfigNode ext = run.object("external_torque");
  ExternalTorqueRun e;
  const nlohmann::json& ids = ext.value("particles");
  if (!ids.is_array() || ids.empty()) ext.fail("particles", "expected a non-empty list of particle ids");
  for (const auto& id : ids) {
    if (!id.is_number_integer()) ext.fail("particles", "expected integer particle ids");
    e.particles.push_back(id.get<std::int64_t>());
  }
  e.beta_torque = ext.positive("torque_kT");
  e.axis = ext.vec3("axis", Vec3::UnitZ());  // the engine's default
  if (!(e.axis.norm() > 0.0)) ext.fail("axis", "expected a non-zero direction");
  e.axis.normalize();
  return e;
}

UnwrappedAngle unwrapped_angle(const ObservableSeries& axes, std::size_t rod, const Vec3& axis) {
  const auto [e1, e2] = in_plane_basis(axis);
  UnwrappedAngle a;
  double previous = 0;
  for (std::size_t r = 0; r < axes.time.size(); ++r) {
    const double* v = &axes.value[r * axes.width + 3 * rod];
    const Vec3 u(v[0], v[1], v[2]);
    const double raw = std::atan2(u.dot(e2), u.dot(e1));
    double theta = raw;
    if (r > 0) {
      double step = std::remainder(raw - previous, 2 * std::numbers::pi);  // in [−π, π]
      if (std::abs(step) > std::numbers::pi / 2) ++a.large_turns;
      theta = a.angle.back() + step;
    }
    previous = raw;
    a.time.push_back(axes.time[r]);
    a.angle.push_back(theta);
    a.mean_axial_square += u.dot(axis) * u.dot(axis);
  }
  if (!a.time.empty()) a.mean_axial_square /= static_cast<double>(a.time.size());
  return a;
}

void TorqueDragAnalysis::accumulate(const Trajectory& t, std::size_t replica) {
  const ExternalTorqueRun e = external_torque_of(t);
  if (replica == 0) {
    r_.torque = e;
  } else if (e.particles != r_.torque.particles || e.beta_torque != r_.torque.beta_torque || !(e.axis - r_.torque.axis).isZero(1e-12)) {
    throw InputError(t.path, kConfigPath + ": external_torque", "expected the external torque of the first replica (particles, torque_kT, axis)");
  }
  const auto it = t.observables.find(kTaggedAxes);
  const std::string where = std::string("/observables/") + kTaggedAxes;
  if (it == t.observables.end())
    throw InputError(t.path, where, "expected the tagged rods' axes (anisodyn-bd records them with external_torque)");
  const ObservableSeries& axes = it->second;
  if (axes.width != 3 * e.particles.size())
    throw InputError(t.path, where + "/value", "expected 3 columns per tagged rod (" + std::to_string(e.particles.size()) + " rods)");
  if (axes.time.size() < 2 * kBlocks)
    throw InputError(t.path, where, "expected at least " + std::to_string(2 * kBlocks) + " rows (in the window) to fit the turning rate");
  const bool blocks = replicas_ == 1 && e.particles.size() == 1;
  r_.time_blocks = blocks;
  for (std::size_t k = 0; k < e.particles.size(); ++k) {
    const auto id = std::find(t.id.begin(), t.id.end(), e.particles[k]);
    if (id == t.id.end()) throw InputError(t.path, kConfigPath + ": external_torque.particles", "no particle with this id in the frames");
    const int s = t.species[static_cast<std::size_t>(id - t.id.begin())];
    if (species_ < 0) species_ = s;
    if (s != species_) throw InputError(t.path, kConfigPath + ": external_torque.particles", "expected tagged rods of one species");
    const UnwrappedAngle a = unwrapped_angle(axes, k, e.axis);
    const std::size_t n = a.time.size();
    TaggedRodDrag rod{replica, e.particles[k], slope(a.time, a.angle, 0, n), a.time.front(), a.time.back(), a.mean_axial_square, n, a.large_turns};
    r_.rods.push_back(rod);
    if (!blocks) {
      samples_.push_back(rod.omega);
      continue;
    }
    for (std::size_t b = 0; b < kBlocks; ++b) samples_.push_back(slope(a.time, a.angle, b * n / kBlocks, (b + 1) * n / kBlocks));
  }
  if (const auto capped = capped_torque_steps(t)) r_.capped_torques = r_.capped_torques.value_or(0.0) + *capped;
  r_.species = t.species_table[static_cast<std::size_t>(species_)].name;
}

TorqueDragResult TorqueDragAnalysis::compute() const {
  TorqueDragResult r = r_;
  r.samples = samples_.size();
  r.omega = mean_and_error(samples_);
  r.dr = {r.omega.value / r.torque.beta_torque, r.omega.error / r.torque.beta_torque};
  return r;
}

}  // namespace anisodyn::analysis
