#include "anisodyn/run/step_loop.hpp"

namespace anisodyn::run {

StepLoop::StepLoop(State& state, StepClient& client, FrameRules frames, std::int64_t observe_every)
    : state_(state), client_(client), frames_(frames), observe_every_(observe_every) {}

void StepLoop::step(io::H5mdWriter& out) {
  const double dt = client_.advance();
  ++step_;
  time_ += dt;
  state_.step = step_;
  state_.time = time_;
  ++steps_since_observation_;
  if (step_ % observe_every_ == 0) observe(out);
  client_.after_step(out, step_, time_);
  if (frames_.due(step_, time_, step_ - last_switch_step_)) write_frame(out);
}

void StepLoop::finish(io::H5mdWriter& out, bool remainder_row) {
  if (remainder_row && steps_since_observation_ > 0) observe(out);
  if (frames_.last_frame_step() != step_) write_frame(out);
}

void StepLoop::observe(io::H5mdWriter& out) {
  client_.observe(out, step_, time_);
  steps_since_observation_ = 0;
}

void StepLoop::write_frame(io::H5mdWriter& out) {
  out.append_frame(client_.frame_state(state_), client_.frame_elements());
  frames_.written_at(step_);
}

nlohmann::json StepLoop::checkpoint_state() const {
  return {{"step", step_},
          {"time", time_},
          {"frames", frames_.to_json()},
          {"last_switch_step", last_switch_step_},
          {"steps_since_observation", steps_since_observation_}};
}

void StepLoop::restore(const nlohmann::json& j) {
  step_ = j.at("step").get<std::int64_t>();
  time_ = j.at("time").get<double>();
  frames_.restore(j.at("frames"));
  last_switch_step_ = j.at("last_switch_step").get<std::int64_t>();
  steps_since_observation_ = j.at("steps_since_observation").get<std::int64_t>();
  state_.step = step_;
  state_.time = time_;
}

}  // namespace anisodyn::run
