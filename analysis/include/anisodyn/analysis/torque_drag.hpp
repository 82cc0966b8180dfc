#pragma once
// Method II of spec 20 §6.2: the self-rotational diffusion D_r(φ) of rods from the drag under a
// constant external torque T_ex = T_ex ê on tagged rods (anisodyn-bd's `external_torque`, whose
// tagged axes are the observable `tagged_axes`). Each tagged axis's in-plane angle about ê,
// θ = atan2(û·ê₂, û·ê₁) with (ê₁, ê₂, ê) right-handed, is unwrapped row by row; ω of a rod is the
// least-squares slope of θ(t). With γ_r(φ)⟨ω⟩ = T_ex and γ_r(φ) = kT/D_r(φ):
//   D_r(φ) = ⟨ω⟩ / (βT_ex).
// The samples are the rods of every replica (ten contiguous time blocks of the rows stand in when
// there is one tagged rod in one replica); the error is their standard error.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"

namespace anisodyn::analysis {

inline constexpr const char* kTaggedAxes = "tagged_axes";

/// The run's external torque, from its parameters (/parameters/config, key external_torque).
struct ExternalTorqueRun {
  std::vector<std::int64_t> particles;  // ids of the tagged rods, in the order of tagged_axes
  double beta_torque = 0;               // βT_ex
  Vec3 axis = Vec3::UnitZ();            // ê
};

/// Reads external_torque from a trajectory's parameters: absent or malformed → InputError naming
/// the file and /parameters/config with the JSON path.
ExternalTorqueRun external_torque_of(const Trajectory& t);

/// θ(t) of one tagged rod, unwrapped: consecutive rows differ by less than π (rows that turn by
/// more than π/2 are counted: the recording is then too sparse to unwrap safely).
struct UnwrappedAngle {
  std::vector<double> time, angle;
  double mean_axial_square = 0;  // ⟨(û·ê)²⟩ over the rows: the confinement check (kT/κ_c for stiff confinement)
  std::size_t large_turns = 0;
};
UnwrappedAngle unwrapped_angle(const ObservableSeries& axes, std::size_t rod, const Vec3& axis);

struct TaggedRodDrag {
  std::size_t replica = 0;
  std::int64_t id = 0;
  double omega = 0, t_start = 0, t_end = 0, mean_axial_square = 0;
  std::size_t rows = 0, large_turns = 0;
};

struct TorqueDragResult {
  std::vector<TaggedRodDrag> rods;
  ExternalTorqueRun torque;
  std::string species;
  Estimate omega, dr;     // ⟨ω⟩ and D_r(φ) = ⟨ω⟩/(βT_ex)
  std::size_t samples = 0;
  bool time_blocks = false;  // one rod in one replica: the samples are blocks of its rows
  std::optional<double> capped_torques;  // particle-steps with a capped torque, all replicas (none: not recorded)
};

class TorqueDragAnalysis {
 public:
  explicit TorqueDragAnalysis(std::size_t replicas) : replicas_(replicas) {}
  void accumulate(const Trajectory& t, std::size_t replica);
  TorqueDragResult compute() const;
  /// The tagged rods' species index in the first replica (for its free D_r).
  int species_index() const { return species_; }

 private:
  std::size_t replicas_;
  TorqueDragResult r_;
  std::vector<double> samples_;
  int species_ = -1;
};

}  // namespace anisodyn::analysis
