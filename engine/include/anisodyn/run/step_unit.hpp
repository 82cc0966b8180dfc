#pragma once
// What one step of an engine is called in configurations: MC and DMC count cycles (N trial moves),
// time-stepping engines (BD, DPD, LB) count steps. The schedule and frame rules are the same for
// all of them; only the key names follow the unit ("cycles" / "every_cycles" / "cycle" vs "steps" /
// "every_steps" / "step").
#include <string>

namespace anisodyn::run {

struct StepUnit {
  std::string plural;    // "cycles"
  std::string singular;  // "cycle"
  std::string time_note;  // what 'time' means in messages, e.g. " (Brownian time, τ)"

  static StepUnit cycles() { return {"cycles", "cycle", " (Brownian time, τ)"}; }
  static StepUnit steps(std::string time_note = "") { return {"steps", "step", std::move(time_note)}; }
  std::string every() const { return "every_" + plural; }
  std::string for_() const { return "for_" + plural; }
};

}  // namespace anisodyn::run
