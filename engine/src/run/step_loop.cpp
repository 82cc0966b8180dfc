#include "anisodyn/run/step_loop.hpp"

#include <algorithm>

namespace anisodyn::run {

StepLoop::StepLoop(State& state, StepClient& client, FrameRules frames, std::int64_t observe_every)
    : state_(state), client_(client), frames_(frames), observe_every_(observe_every) {}

void StepLoop::step(io::H5mdWriter& out) { count_step(out, client_.advance()); }

std::int64_t StepLoop::quiet_steps(std::int64_t wanted, double dt) const {
  FrameClock frames = frames_;  // due() advances the time-based rules: ask a copy
  double t = time_;
  for (std::int64_t j = 1; j < wanted; ++j) {
    const std::int64_t s = step_ + j;
    t += dt;
    if (s % observe_every_ == 0 || frames.due(s, t, s - last_switch_step_)) return j;
  }
  return std::max<std::int64_t>(wanted, 1);
}

void StepLoop::steps(io::H5mdWriter& out, std::int64_t k) {
  if (k <= 1) {
    step(out);
    return;
  }
  const double dt = client_.advance_steps(k);
  for (std::int64_t j = 1; j <= k; ++j) {
    const std::int64_t observations = steps_since_observation_;
    const std::int64_t frame = frames_.last_frame_step();
    count_step(out, dt);
    if (j < k && (steps_since_observation_ <= observations || frames_.last_frame_step() != frame))
      throw std::logic_error("StepLoop::steps: an observation or a frame fell due inside a batch (use quiet_steps)");
  }
}

void StepLoop::count_step(io::H5mdWriter& out, double dt) {
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
