#include "anisodyn/run/frame_rules.hpp"

#include <cmath>

namespace anisodyn::run {

bool FrameRules::log_step_due(std::int64_t since_switch) const {
  if (!(log_steps_per_decade > 0.0) || since_switch < 0) return false;
  const std::int64_t m = log_steps_restart > 0 ? since_switch % log_steps_restart : since_switch;
  if (m == 0) return true;
  // m is on the grid if round(10^(k/n)) = m for the k nearest n·log10(m)
  const double x = log_steps_per_decade * std::log10(static_cast<double>(m));
  for (auto k = static_cast<std::int64_t>(std::floor(x)) - 1; k <= static_cast<std::int64_t>(std::ceil(x)) + 1; ++k)
    if (k >= 0 && std::llround(std::pow(10.0, static_cast<double>(k) / log_steps_per_decade)) == m) return true;
  return false;
}

FrameRules parse_frame_rules(tool::ConfigNode& cfg, const StepUnit& unit, FrameUse use) {
  FrameRules r;
  auto f = cfg.optional_object("frames");
  if (!f) return r;
  for (const char* key : {"every_time", "log_first_time", "log_per_decade", "after_switch"})
    f->reject_unless(use == FrameUse::Production, key,
                     "in a preparation run, which has no time and no field switches (use " + unit.every() + " or log_" + unit.plural + ")");
  r.every_steps = f->non_negative_integer(unit.every(), 0);
  r.every_time = f->non_negative("every_time", 0.0);
  if (f->has("log_per_decade") || f->has("log_first_time")) {
    r.log_per_decade = f->positive("log_per_decade");
    r.log_first_time = f->positive("log_first_time");
  }
  if (auto a = f->optional_object("after_switch")) {
    r.after_switch_every = a->positive_integer(unit.every());
    r.after_switch_for = a->positive_integer(unit.for_());
  }
  if (auto l = f->optional_object("log_" + unit.plural)) {
    r.log_steps_per_decade = l->positive("per_decade");
    if (l->has("restart_every")) r.log_steps_restart = l->positive_integer("restart_every");
  }
  return r;
}

bool FrameClock::due(std::int64_t step, double time, std::int64_t since_switch) {
  const FrameRules& f = rules_;
  bool due = f.every_steps > 0 && step % f.every_steps == 0;
  if (f.after_switch_every > 0 && since_switch <= f.after_switch_for && since_switch % f.after_switch_every == 0) due = true;
  if (f.log_step_due(since_switch)) due = true;
  if (f.every_time > 0.0 && time >= static_cast<double>(next_time_frame_) * f.every_time) {
    due = true;
    while (static_cast<double>(next_time_frame_) * f.every_time <= time) ++next_time_frame_;
  }
  if (f.log_per_decade > 0.0) {
    auto log_time = [&](std::int64_t k) { return f.log_first_time * std::pow(10.0, static_cast<double>(k) / f.log_per_decade); };
    if (time >= log_time(next_log_frame_)) {
      due = true;
      while (log_time(next_log_frame_) <= time) ++next_log_frame_;
    }
  }
  return due;
}

nlohmann::json FrameClock::to_json() const {
  return {{"next_log_frame", next_log_frame_}, {"next_time_frame", next_time_frame_}, {"last_frame_step", last_frame_step_}};
}

void FrameClock::restore(const nlohmann::json& j) {
  next_log_frame_ = j.at("next_log_frame").get<std::int64_t>();
  next_time_frame_ = j.at("next_time_frame").get<std::int64_t>();
  last_frame_step_ = j.at("last_frame_step").get<std::int64_t>();
}

}  // namespace anisodyn::run
