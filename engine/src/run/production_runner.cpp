#include "anisodyn/run/production_runner.hpp"

#include <cstdio>
#include <utility>

#include "anisodyn/core/progress.hpp"

namespace anisodyn::run {

ProductionRunner::ProductionRunner(State& state, ProductionClient& client, ProductionSettings settings, bool quiet)
    : client_(client),
      label_(std::move(settings.label)),
      unit_(std::move(settings.unit)),
      quiet_(quiet),
      schedule_(std::move(settings.schedule)),
      loop_(state, client, settings.frames, settings.observe_every) {}

void ProductionRunner::run(io::H5mdWriter& out, CheckpointClock& checkpoints, std::int64_t steps_before) {
  Progress progress(label_ + " (per mille of the schedule)", 1000, quiet_);
  if (!schedule_.started()) start_segment(out);
  while (true) {
    if (schedule_.segment_done(step(), time())) {
      if (!schedule_.next()) break;
      start_segment(out);
    }
    loop_.step(out);
    char detail[96];
    std::snprintf(detail, sizeof detail, "t=%.4g field=%s", time(), client_.field_on() ? "on" : "off");
    progress.update(static_cast<std::int64_t>(1000.0 * schedule_.fraction(step(), time())), detail);
    checkpoints.tick(steps_before + step(), "production " + unit_.singular + " " + std::to_string(step()));
  }
  loop_.finish(out, true);
  progress.finish();
}

void ProductionRunner::start_segment(io::H5mdWriter& out) {
  const bool first = schedule_.first_segment();
  const bool on = schedule_.current().field_on;
  schedule_.start(step(), time());
  if (first || on != client_.field_on()) switch_field(out, on);
  if (first && step() == 0) loop_.write_frame(out);
}

void ProductionRunner::switch_field(io::H5mdWriter& out, bool on) {
  const Vec3 e = client_.switch_field(on, step());
  out.append_observable("field_switches", step(), time(), std::vector<double>{on ? 1.0 : 0.0, e.x(), e.y(), e.z()});
  out.set_observable_attribute("field_switches", "definition",
                               "field state after a switch (1 on, 0 off) and the field direction x, y, z; the first row is the initial state");
  out.set_observable_attribute("field_switches", "units", "1");
  switches_.push_back({{unit_.singular, step()}, {"time", time()}, {"field", on ? "on" : "off"}});
  loop_.mark_switch();
}

nlohmann::json ProductionRunner::checkpoint_state() const {
  nlohmann::json j = loop_.checkpoint_state();
  j["schedule"] = schedule_.position().to_json();
  j["switches"] = switches_;
  return j;
}

void ProductionRunner::restore(const nlohmann::json& j) {
  loop_.restore(j);
  schedule_.restore(SchedulePosition::from_json(j.at("schedule")));
  switches_ = j.at("switches");
}

}  // namespace anisodyn::run
