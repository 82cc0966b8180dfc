#include "anisodyn/run/production_runner.hpp"

#include <cstdio>

#include "anisodyn/core/progress.hpp"

namespace anisodyn::run {

ProductionRunner::ProductionRunner(State& state, ProductionClient& client, ProductionSettings settings, bool quiet)
    : state_(state),
      client_(client),
      settings_(std::move(settings)),
      quiet_(quiet),
      schedule_(settings_.schedule),
      frames_(settings_.frames) {}

void ProductionRunner::run(io::H5mdWriter& out, CheckpointClock& checkpoints, std::int64_t steps_before) {
  Progress progress(settings_.label + " (per mille of the schedule)", 1000, quiet_);
  if (!schedule_.started()) start_segment(out);
  while (true) {
    if (schedule_.segment_done(step_, time_)) {
      if (!schedule_.next()) break;
      start_segment(out);
    }
    one_step(out);
    char detail[96];
    std::snprintf(detail, sizeof detail, "t=%.4g field=%s", time_, client_.field_on() ? "on" : "off");
    progress.update(static_cast<std::int64_t>(1000.0 * schedule_.fraction(step_, time_)), detail);
    checkpoints.tick(steps_before + step_, "production " + settings_.unit.singular + " " + std::to_string(step_));
  }
  if (steps_since_observation_ > 0) observe(out);
  if (frames_.last_frame_step() != step_) write_frame(out);
  progress.finish();
}

void ProductionRunner::start_segment(io::H5mdWriter& out) {
  const bool first = schedule_.first_segment();
  const bool on = schedule_.current().field_on;
  schedule_.start(step_, time_);
  if (first || on != client_.field_on()) switch_field(out, on);
  if (first && step_ == 0) write_frame(out);
}

void ProductionRunner::switch_field(io::H5mdWriter& out, bool on) {
  const Vec3 e = client_.switch_field(on, step_);
  out.append_observable("field_switches", step_, time_, std::vector<double>{on ? 1.0 : 0.0, e.x(), e.y(), e.z()});
  out.set_observable_attribute("field_switches", "definition",
                               "field state after a switch (1 on, 0 off) and the field direction x, y, z; the first row is the initial state");
  out.set_observable_attribute("field_switches", "units", "1");
  switches_.push_back({{settings_.unit.singular, step_}, {"time", time_}, {"field", on ? "on" : "off"}});
  last_switch_step_ = step_;
}

void ProductionRunner::one_step(io::H5mdWriter& out) {
  const double dt = client_.advance();
  ++step_;
  time_ += dt;
  state_.step = step_;
  state_.time = time_;
  ++steps_since_observation_;
  if (step_ % settings_.observe_every == 0) observe(out);
  client_.after_step(out, step_, time_);
  if (frames_.due(step_, time_, step_ - last_switch_step_)) write_frame(out);
}

void ProductionRunner::observe(io::H5mdWriter& out) {
  client_.observe(out, step_, time_);
  steps_since_observation_ = 0;
}

void ProductionRunner::write_frame(io::H5mdWriter& out) {
  out.append_frame(state_, client_.frame_elements());
  frames_.written_at(step_);
}

nlohmann::json ProductionRunner::checkpoint_state() const {
  return {{"step", step_},
          {"time", time_},
          {"schedule", schedule_.position().to_json()},
          {"frames", frames_.to_json()},
          {"last_switch_step", last_switch_step_},
          {"steps_since_observation", steps_since_observation_},
          {"switches", switches_}};
}

void ProductionRunner::restore(const nlohmann::json& j) {
  step_ = j.at("step").get<std::int64_t>();
  time_ = j.at("time").get<double>();
  schedule_.restore(SchedulePosition::from_json(j.at("schedule")));
  frames_.restore(j.at("frames"));
  last_switch_step_ = j.at("last_switch_step").get<std::int64_t>();
  steps_since_observation_ = j.at("steps_since_observation").get<std::int64_t>();
  switches_ = j.at("switches");
  state_.step = step_;
  state_.time = time_;
}

}  // namespace anisodyn::run
