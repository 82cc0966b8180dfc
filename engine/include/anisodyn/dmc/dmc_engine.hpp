#pragma once
// Dynamic Monte Carlo (spec 10 §4): Metropolis moves whose maximum sizes follow from the
// infinite-dilution diffusion coefficients, δ² = 2 D δt_MC, so that the accepted moves reproduce
// Brownian dynamics with the time mapping t = (δt_MC/3) Σ_cycles A. Only physical moves: one
// particle picked at random (with replacement) per trial, N trials per cycle; anisotropic particles
// make one combined roto-translation per trial; a pulled tracer feels a constant force.
//
// The engine does one cycle at a time and reports what was tried and accepted per species; the
// time mapping and the balancing of the species' time steps live in time_balance.hpp.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/dipolar_ewald.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/interactions/orientational_field.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// How the three body-frame rotation angles of a trial are composed (spec 10 §4.2).
enum class RotationComposition {
  ExponentialMap,  // one rotation by the body-frame rotation vector θ: O' = O·exp([θ]×) (default)
  Sequential       // three successive rotations about the current body axes, in `sequential_order`
};
/// Body frame in which a trial's translation components are applied.
enum class TranslationFrame {
  Midpoint,  // axes of the orientation halfway through the rotation: a symmetric proposal (default)
  Old        // axes before the rotation, as printed in the papers
};

struct DmcMoveOptions {
  RotationComposition rotation = RotationComposition::ExponentialMap;
  std::array<int, 3> sequential_order{0, 2, 1};  // body axes 0 = T, 1 = W, 2 = L; default T, L, W
  TranslationFrame frame = TranslationFrame::Midpoint;
};

/// A constant force βF along +box axis `axis` on one particle (spec 10 §4.5): βU = −βF z.
struct PulledTracer {
  std::int32_t particle = -1;
  int axis = 2;
  double beta_force = 0.0;
  bool active() const { return particle >= 0; }
};

/// Trials of one species: tried, passed the overlap test, accepted.
struct TrialCounts {
  std::int64_t tried = 0, passed = 0, accepted = 0;
  void add(const TrialCounts& o) { tried += o.tried; passed += o.passed; accepted += o.accepted; }
  double acceptance() const { return tried > 0 ? static_cast<double>(accepted) / static_cast<double>(tried) : 0.0; }
  double pass_fraction() const { return tried > 0 ? static_cast<double>(passed) / static_cast<double>(tried) : 0.0; }
};

/// Dipoles on some species, present only while the field is on (spec 10 §6).
struct DipoleSettings {
  double gamma = 0.0;
  std::vector<char> species_carries;  // per species
  EwaldParameters ewald;
  bool active() const { return gamma != 0.0; }
};

class DmcEngine {
 public:
  /// Works on `state` in place. Throws InputError if the configuration overlaps or a species that
  /// can move has no diffusion coefficients.
  DmcEngine(State& state, const RngState& rng, const DmcMoveOptions& options);

  /// δt_MC per species; recomputes the maximum moves δ = √(2 D δt_MC).
  void set_time_steps(const std::vector<double>& dt);
  const std::vector<double>& time_steps() const { return dt_; }

  /// The orientational field and the dipoles act only while the field is switched on.
  void set_orientational_field(const OrientationalField& field) { field_ = field; }
  OrientationalField& orientational_field() { return field_; }
  void set_dipoles(const DipoleSettings& dipoles, const Vec3& direction);
  /// Switching on (re)builds the Ewald structure factor from the current positions.
  void set_field_on(bool on);
  bool field_on() const { return field_on_; }

  void set_tracer(const PulledTracer& tracer);
  const PulledTracer& tracer() const { return tracer_; }
  /// Largest tracer step along the force, √(2Dδt + (DβFδt)²), and the validity parameter βF δx_∥.
  double tracer_parallel_step() const;

  /// One cycle: N trials. Counts per species are in last_cycle().
  void cycle();
  const std::vector<TrialCounts>& last_cycle() const { return cycle_counts_; }

  /// Total βU of the orientational field (0 while off) and of the dipoles (0 while off; kept as
  /// the Ewald energy at switch-on plus the accepted ΔU).
  double field_energy() const;
  double dipolar_energy() const { return field_on_ && ewald_ ? dipolar_energy_ : 0.0; }

  /// Per-particle accumulators (spec 10 §4.6): Σ body-frame displacements (N×3), Σ body-frame
  /// rotation angles (N×3), and the accumulated lab-frame rotation vector of each body axis (N×9).
  const std::vector<double>& body_displacement() const { return body_displacement_; }
  const std::vector<double>& body_rotation() const { return body_rotation_; }
  const std::vector<double>& rotation_vectors() const { return rotation_vector_; }
  /// Zeroes the per-particle accumulators, so that they count from the start of production (the
  /// preliminary balancing cycles are not part of the trajectory).
  void reset_accumulators();

  /// Everything needed to continue bit-for-bit (the configuration itself is saved separately).
  nlohmann::json checkpoint() const;
  void restore(const nlohmann::json& j);
  const RngState& rng_state() const { return rng_.state(); }
  const State& state() const { return state_; }
  const HardOverlap& overlap() const { return overlap_; }

 private:
  void trial();
  void roto_translation(std::int32_t i, int s, TrialCounts& c);
  void translation(std::int32_t i, int s, TrialCounts& c);
  void tracer_move(std::int32_t i, int s, TrialCounts& c);
  /// Metropolis test on βΔU with a uniform drawn before the overlap test.
  static bool metropolis(double dU, double u) { return dU <= 0.0 || u < std::exp(-dU); }
  void commit(std::int32_t i, const Vec3& r, const Int3& image, const Quat& q, const Mat3& rot_new);
  void accumulate_rotation_vectors(std::size_t i, const Mat3& old_rot, const Mat3& new_rot);
  /// Skin lists for the anisotropic species, sized from the current moves (kept while the moves
  /// stay within a factor two of those they were sized for, so per-cycle δt changes are free).
  void size_skin_lists();

  State& state_;
  Rng rng_;
  DmcMoveOptions options_;
  HardOverlap overlap_;
  std::vector<double> dt_;
  std::vector<Vec3> translate_cap_, rotate_cap_;
  std::vector<char> anisotropic_;
  std::vector<double> skin_request_;  // half-skins last asked of overlap_
  OrientationalField field_;
  bool field_on_ = false;
  DipoleSettings dipoles_;
  Vec3 dipole_direction_ = Vec3::UnitZ();
  std::unique_ptr<DipolarEwald> ewald_;
  double dipolar_energy_ = 0.0;
  PulledTracer tracer_;
  std::vector<TrialCounts> cycle_counts_;
  std::vector<double> body_displacement_, body_rotation_, rotation_vector_;
};

}  // namespace anisodyn
