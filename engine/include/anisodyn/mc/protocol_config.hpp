#pragma once
// The anisodyn-mc configuration (docs/mc.md):
//   {"seed": 1, "target_acceptance": 0.35, "tune_every": 100, "observe_every": 10,
//    "frames": {"every_cycles": 5000},                           (run/frame_rules.hpp)
//    "field": {"direction": [1, 0, 0], "orientational": {"strength": 3, "axis": "W"}},  (run/field_config.hpp)
//    "phases": [{"type": "compress", "packing_fraction": 0.34},
//               {"type": "nvt", "cycles": 20000, "tune": true},
//               {"type": "nvt", "cycles": 50000, "expect_phase": "nematic"}]}
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/mc/protocol.hpp"

namespace anisodyn {

/// Reads the protocol from the tool configuration.
McProtocol parse_mc_protocol(tool::ConfigNode& cfg);

}  // namespace anisodyn
