#pragma once
// Profiles of a DPD liquid (spec 30 §6, §8), summed over the steps of an observation row and written
// as the row's means:
//   profile_z_count, profile_z_vx_sum            per slab [k w, (k + 1) w) of z (w = z_bin): the
//                                                number of liquid particles and their Σ v_x;
//   profile_r_count                              per shell [k w, (k + 1) w) of the distance from
//                                                the first colloid's centre (w = radial_bin, out to
//                                                radial_max): the number;
//   profile_r_midplane_count, _vx_sum            the same shells within the mid-plane slab
//                                                |x − x_c| < midplane_half_width: number and Σ v_x.
// anisodyn-flow turns them into ρ(z), v_x(z), the slip length, ρ(r) and v_x(r) (docs/analysis.md).
// The sums are part of the checkpoint (to_json), so a resumed run writes the same rows.
#include <cstdint>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/box.hpp"
#include "anisodyn/dpd/dpd_protocol.hpp"
#include "anisodyn/io/h5md.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

class FlowProfiles {
 public:
  explicit FlowProfiles(DpdProtocol::Profiles settings) : settings_(settings) {}

  /// Adds one step of the liquid particles `liquid` (state indices) of s; `centre`: the first
  /// colloid's position, needed by the radial profiles.
  void add(const State& s, std::span<const std::int32_t> liquid, const Vec3& centre);
  /// Appends the row's means (sums / steps) to the output's observables and starts a new row.
  void write(io::H5mdWriter& out, std::int64_t step, double time, double steps);
  /// The observables' units, definitions and bin widths.
  void describe(io::H5mdWriter& out, const Box& box) const;

  nlohmann::json to_json() const;
  void restore(const nlohmann::json& j);

 private:
  /// The radial profiles' reach: radial_max, or half the shortest box edge.
  double radial_max(const Box& box) const;

  DpdProtocol::Profiles settings_;
  // Σ over the row's steps (empty until the first step).
  std::vector<double> z_count_, z_vx_, r_count_, r_mid_count_, r_mid_vx_;
};

}  // namespace anisodyn
