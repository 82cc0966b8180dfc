#include "anisodyn/dpd/flow_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace anisodyn {

void FlowProfiles::add(const State& s, std::span<const std::int32_t> liquid, const Vec3& centre) {
  const Particles& p = s.particles;
  if (settings_.z_bin > 0.0) {
    const std::size_t bins = static_cast<std::size_t>(std::ceil(s.box.edges().z() / settings_.z_bin));
    z_count_.resize(bins, 0.0);
    z_vx_.resize(bins, 0.0);
    for (const std::int32_t index : liquid) {
      const auto i = static_cast<std::size_t>(index);
      const auto b = std::min(bins - 1, static_cast<std::size_t>(p.z[i] / settings_.z_bin));
      z_count_[b] += 1.0;
      z_vx_[b] += p.vx[i];
    }
  }
  if (settings_.radial_bin > 0.0) {
    const double r_max = radial_max(s.box);
    const std::size_t bins = static_cast<std::size_t>(std::ceil(r_max / settings_.radial_bin - 1e-9));
    for (auto* v : {&r_count_, &r_mid_count_, &r_mid_vx_}) v->resize(bins, 0.0);
    for (const std::int32_t index : liquid) {
      const auto i = static_cast<std::size_t>(index);
      const Vec3 d = s.box.min_image(p.position(i) - centre);
      const double r = d.norm();
      if (r >= r_max) continue;
      const auto b = static_cast<std::size_t>(r / settings_.radial_bin);
      r_count_[b] += 1.0;
      if (std::abs(d.x()) < settings_.midplane_half_width) {
        r_mid_count_[b] += 1.0;
        r_mid_vx_[b] += p.vx[i];
      }
    }
  }
}

double FlowProfiles::radial_max(const Box& box) const {
  return settings_.radial_max > 0.0 ? settings_.radial_max : 0.5 * box.shortest_edge();
}

void FlowProfiles::write(io::H5mdWriter& out, std::int64_t step, double time, double steps) {
  auto mean = [&](const std::vector<double>& v) {
    std::vector<double> m(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) m[k] = v[k] / steps;
    return m;
  };
  if (!z_count_.empty()) {
    out.append_observable("profile_z_count", step, time, mean(z_count_));
    out.append_observable("profile_z_vx_sum", step, time, mean(z_vx_));
  }
  if (!r_count_.empty()) {
    out.append_observable("profile_r_count", step, time, mean(r_count_));
    out.append_observable("profile_r_midplane_count", step, time, mean(r_mid_count_));
    out.append_observable("profile_r_midplane_vx_sum", step, time, mean(r_mid_vx_));
  }
  for (auto* v : {&z_count_, &z_vx_, &r_count_, &r_mid_count_, &r_mid_vx_}) v->clear();
}

void FlowProfiles::describe(io::H5mdWriter& out, const Box& box) const {
  auto attr = [&](const std::string& name, const std::string& units, const std::string& definition) {
    out.set_observable_attribute(name, "units", units);
    out.set_observable_attribute(name, "definition", definition);
  };
  const Vec3 L = box.edges();
  if (settings_.z_bin > 0.0) {
    const std::string slabs = "per slab [k w, (k + 1) w) of z, w = z_bin = " + std::to_string(settings_.z_bin) + ", area " +
                              std::to_string(L.x() * L.y()) + ", mean over the row's steps";
    attr("profile_z_count", "1", "number of liquid particles " + slabs);
    attr("profile_z_vx_sum", "r_c/tau", "sum of v_x of the liquid particles " + slabs);
    for (const char* name : {"profile_z_count", "profile_z_vx_sum"}) out.set_observable_attribute(name, "bin_width", std::to_string(settings_.z_bin));
  }
  if (settings_.radial_bin > 0.0) {
    const std::string shells = "per shell [k w, (k + 1) w) of the distance r from the first colloid's centre, w = radial_bin = " +
                               std::to_string(settings_.radial_bin) + ", mean over the row's steps";
    const std::string mid = " with |x - x_c| < " + std::to_string(settings_.midplane_half_width) + " (the mid-plane slab)";
    attr("profile_r_count", "1", "number of liquid particles " + shells);
    attr("profile_r_midplane_count", "1", "number of liquid particles" + mid + ", " + shells);
    attr("profile_r_midplane_vx_sum", "r_c/tau", "sum of v_x of the liquid particles" + mid + ", " + shells);
    for (const char* name : {"profile_r_count", "profile_r_midplane_count", "profile_r_midplane_vx_sum"}) {
      out.set_observable_attribute(name, "bin_width", std::to_string(settings_.radial_bin));
      out.set_observable_attribute(name, "midplane_half_width", std::to_string(settings_.midplane_half_width));
    }
  }
}

nlohmann::json FlowProfiles::to_json() const {
  return {{"z_count", z_count_}, {"z_vx", z_vx_}, {"r_count", r_count_}, {"r_mid_count", r_mid_count_}, {"r_mid_vx", r_mid_vx_}};
}

void FlowProfiles::restore(const nlohmann::json& j) {
  for (auto [key, v] : {std::pair{"z_count", &z_count_}, {"z_vx", &z_vx_}, {"r_count", &r_count_}, {"r_mid_count", &r_mid_count_},
                        {"r_mid_vx", &r_mid_vx_}})
    *v = j.at(key).get<std::vector<double>>();
}

}  // namespace anisodyn
