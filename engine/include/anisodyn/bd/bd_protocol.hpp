#pragma once
// The anisodyn-bd configuration (docs/bd.md):
//   {"seed": 1, "time_step": 5e-8, "steps": 100000 | "time": 0.005,
//    "units": {"system": "reduced"} | {"system": "SI", "length": 1e-6, "temperature": 300},
//    "species": {"rod": {"D_trans": [..], "D_rot": [..]} | {"diffusion_from": {..}}},   (io/diffusion_overrides.hpp)
//    "slender_body": {"rod": {"viscosity": 1e-3, "diameter": 0.0148}},   (bd/slender_body.hpp; diameter optional)
//    "frames": {...}, "observe_every": 100,                                           (run/frame_rules.hpp)
//    "potential": {"type": "overlap_volume", "species": "rod", "hardness": 17.71, "finite_length":
//                  "segment_distance" | "interior_only", "skin": 0.04}                        (spec 20 §4)
//               | {"type": "mie", "species": ["hs"], "exponent": 50, "epsilon_kT": 1,
//                  "sigma": "diameter" | "barker_henderson", "skin": 0.1},        (interactions/mie_pairs.hpp)
//    "tracer": {"species": "tracer", "pe": 1, "axis": "z", "record_every": 10},   (run/pulled_tracer.hpp)
//    "external_torque": {"particles": [0], "torque_kT": 10, "axis": [0, 0, 1], "confinement_kT": 100,
//                        "record_every": 10},                                             (spec 20 §6.2)
//    "caps": {"force": "step_bound" | number | null, "torque": "step_bound" | number | null}}
// Time is in the unit system's time (τ reduced, s in SI); lengths in the input's unit (SI: `length`
// metres each); energies in kT (reduced) or J (SI, kT = k_B T).
#include <cstdint>
#include <map>
#include <string>
#include <optional>
#include <vector>

#include "anisodyn/io/diffusion_overrides.hpp"
#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/pulled_tracer.hpp"
#include "anisodyn/run/schedule.hpp"
#include "anisodyn/run/time_step_run.hpp"
#include "anisodyn/system/state.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/tool/unit_system.hpp"

namespace anisodyn {

/// The run's unit system (tool/unit_system.hpp): reduced or SI.
using BdUnits = tool::UnitSystem;

/// A cap on the norm of a rod's systematic force or torque (spec 20 §4.5).
struct BdCap {
  enum class Kind { None, StepBound, Value } kind = Kind::StepBound;
  double value = 0.0;  // Kind::Value, in the run's units
};

/// Free-rod diffusion from the slender-body formulas (spec 20 §2) instead of the species table.
struct SlenderBodySpec {
  double viscosity = 0.0;           // Pa s in SI, kT τ/σ³ reduced
  std::optional<double> diameter;   // in ln(L/D); default the species' diameter (the spec's flag for D_eff)
  std::string path;                 // JSON path, for errors found against the input
};

/// The rod–rod overlap-volume potential (spec 20 §4); absent: free particles.
struct OverlapVolumeSpec {
  std::string species;             // the rod species; empty: the input's only spherocylinder species
  std::optional<double> hardness;  // k in kT/D³ (D the bare diameter); default: k f(0.8D) = kT
  bool interior_only = false;      // the finite-length rule (default: segment distance)
  std::optional<double> skin;      // Verlet-list skin in length units; default L/20
  std::string path = "potential";
};

/// The pseudo-hard sphere core between spheres (interactions/mie_pairs.hpp); absent: free spheres.
struct MieSpec {
  std::vector<std::string> species;  // the interacting sphere species; empty: every sphere species
  double exponent = 50.0;            // n; the attractive exponent is n − 1
  double epsilon_kT = 1.0;           // βε
  bool barker_henderson = false;     // σ such that the Barker–Henderson diameter is the sphere's diameter
  std::optional<double> skin;        // Verlet-list skin; default a tenth of the largest diameter
  std::string path = "potential";
};

/// Method II (spec 20 §6.2): a constant torque on tagged rods, confined to the plane ⊥ the torque.
struct ExternalTorqueSpec {
  std::vector<std::int64_t> particles;  // ids of the tagged rods
  double torque_kT = 0.0;               // βT_ex
  Vec3 axis = Vec3::UnitZ();            // direction of T_ex
  double confinement_kT = 0.0;          // βκ_c
  std::int64_t record_every = 1;        // steps between rows of the tagged axes
};

struct BdProtocol : run::TimeStepRun {
  BdUnits units;
  io::DiffusionOverrides diffusion;
  std::map<std::string, SlenderBodySpec> slender_body;
  std::optional<OverlapVolumeSpec> potential;   // rods
  std::optional<MieSpec> sphere_potential;      // spheres
  std::optional<ExternalTorqueSpec> external_torque;
  std::optional<run::PulledTracerSpec> tracer;
  BdCap force_cap, torque_cap;
};

BdProtocol parse_bd_protocol(tool::ConfigNode& cfg);

}  // namespace anisodyn
