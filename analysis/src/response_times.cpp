#include "anisodyn/analysis/response_times.hpp"

#include <algorithm>
#include <cmath>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kSwitches = "/observables/field_switches";

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

double mean_of(const std::vector<double>& x, std::size_t from, std::size_t to) {
  double s = 0;
  for (std::size_t i = from; i < to; ++i) s += x[i];
  return to > from ? s / static_cast<double>(to - from) : kNaN;
}

/// Frame index range [first, last) of the frames with lo ≤ t < hi.
std::pair<std::size_t, std::size_t> segment(const std::vector<double>& time, double lo, double hi) {
  const auto a = std::lower_bound(time.begin(), time.end(), lo);
  const auto b = std::lower_bound(time.begin(), time.end(), hi);
  return {static_cast<std::size_t>(a - time.begin()), static_cast<std::size_t>(std::max(a, b) - time.begin())};
}

/// First time (measured from t0) at which the smoothed segment y reaches the threshold, upward
/// (y ≥ thr) or downward (y ≤ thr), interpolated linearly between the bracketing frames; NaN if never.
double first_crossing(const std::vector<double>& t, const std::vector<double>& y, double t0, double thr, bool upward) {
  for (std::size_t i = 0; i < y.size(); ++i) {
    const bool reached = upward ? y[i] >= thr : y[i] <= thr;
    if (!reached) continue;
    if (i == 0 || y[i] == y[i - 1]) return t[i] - t0;
    const double w = (thr - y[i - 1]) / (y[i] - y[i - 1]);
    return t[i - 1] + w * (t[i] - t[i - 1]) - t0;
  }
  return kNaN;
}

/// Frames of the centred moving average over `fraction` of a segment: at least 1, made odd.
std::size_t smoothing_window(std::size_t frames, double fraction) {
  const auto w = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(fraction * static_cast<double>(frames))));
  return 2 * (w / 2) + 1;
}
}  // namespace

SwitchCycle switch_cycle_from_observable(const ObservableSeries& sw, std::size_t cycle, const std::string& path) {
  const std::size_t rows = sw.time.size(), w = sw.width;
  auto on = [&](std::size_t r) { return sw.value[r * w] > 0.5; };
  SwitchCycle c;
  if (rows == 0) throw InputError(path, kSwitches, "the field_switches observable is empty");
  bool state = on(0);
  double last_off = -INFINITY;
  std::size_t count = 0;
  for (std::size_t r = 1; r < rows; ++r) {
    const bool now = on(r);
    if (now && !state) {
      if (count == cycle && std::isnan(c.on)) {
        c.on = sw.time[r];
        c.reference_start = last_off;
        if (w >= 4) {
          const Vec3 e(sw.value[r * w + 1], sw.value[r * w + 2], sw.value[r * w + 3]);
          if (e.norm() > 0) c.field = e.normalized();
        }
      } else if (!std::isnan(c.on) && !std::isnan(c.off)) {
        c.end = sw.time[r];
        break;
      }
      ++count;
    }
    if (!now && state) {
      if (!std::isnan(c.on) && std::isnan(c.off)) c.off = sw.time[r];
      last_off = sw.time[r];
    }
    state = now;
  }
  if (std::isnan(c.on))
    throw InputError(path, kSwitches, "no switch-on number " + std::to_string(cycle) + " (the observable records " + std::to_string(count) +
                                          " switch-on(s); the first row is the initial state)");
  return c;
}

std::vector<double> moving_average(const std::vector<double>& x, std::size_t window) {
  const std::size_t half = window / 2;
  std::vector<double> out(x.size());
  std::vector<double> prefix(x.size() + 1, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) prefix[i + 1] = prefix[i] + x[i];
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::size_t a = i >= half ? i - half : 0, b = std::min(x.size(), i + half + 1);
    out[i] = (prefix[b] - prefix[a]) / static_cast<double>(b - a);
  }
  return out;
}

ReplicaResponse response_times(const std::vector<double>& time, const std::vector<double>& signal, const SwitchCycle& c,
                               const ResponseParameters& p) {
  ReplicaResponse r;
  r.switch_on = c.on;
  r.switch_off = c.off;
  const bool has_off = !std::isnan(c.off);
  const auto ref = segment(time, c.reference_start, c.on);
  const auto on = segment(time, c.on, has_off ? c.off : c.end);
  const auto off = has_off ? segment(time, c.off, c.end) : std::pair<std::size_t, std::size_t>{0, 0};
  r.reference_frames = ref.second - ref.first;
  r.on_frames = on.second - on.first;
  r.off_frames = off.second - off.first;
  r.b_eq_off = mean_of(signal, ref.first, ref.second);
  auto piece = [](const std::vector<double>& v, std::pair<std::size_t, std::size_t> s) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(s.first), v.begin() + static_cast<std::ptrdiff_t>(s.second));
  };
  if (r.on_frames > 0) {
    const std::size_t tail = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(p.on_tail_fraction * static_cast<double>(r.on_frames))));
    r.b_on = mean_of(signal, on.second - tail, on.second);
    r.window_on = smoothing_window(r.on_frames, p.smoothing_fraction);
    const auto y = moving_average(piece(signal, on), r.window_on);
    r.t_on = first_crossing(piece(time, on), y, c.on, p.on_fraction * r.b_on, true);
  }
  if (r.off_frames > 0) {
    r.window_off = smoothing_window(r.off_frames, p.smoothing_fraction);
    const auto y = moving_average(piece(signal, off), r.window_off);
    const auto t = piece(time, off);
    if (!std::isnan(r.b_eq_off)) {
      r.t_off = first_crossing(t, y, c.off, p.off_factor * r.b_eq_off, false);
      if (!std::isnan(r.b_on)) r.t_off95 = first_crossing(t, y, c.off, r.b_eq_off + p.off_margin * (r.b_on - r.b_eq_off), false);
    }
  }
  return r;
}

OutlierRejection reject_outliers(const std::vector<double>& t, double threshold) {
  OutlierRejection o;
  o.score.assign(t.size(), kNaN);
  o.rejected.assign(t.size(), 0);
  o.one_sided.assign(t.size(), 0);
  std::vector<double> finite;
  for (double v : t)
    if (std::isfinite(v)) finite.push_back(v);
  o.missing = t.size() - finite.size();
  if (finite.empty()) return o;
  const double med = median(finite);
  std::vector<double> dev;
  double mean_dev = 0;
  for (double v : finite) {
    dev.push_back(std::abs(v - med));
    mean_dev += std::abs(v - med) / static_cast<double>(finite.size());
  }
  const double mad = median(dev);
  // MAD = 0 (more than half the values equal): Iglewicz & Hoaglin's fallback uses the mean absolute
  // deviation, M = (t − t̃)/(1.253314 · MeanAD); if that is 0 too, every value is the median.
  double scale = mad > 0 ? mad / 0.6745 : 1.253314 * mean_dev;
  o.mean_absolute_deviation = !(mad > 0);
  std::vector<double> kept;
  for (std::size_t j = 0; j < t.size(); ++j) {
    if (!std::isfinite(t[j])) continue;
    o.score[j] = scale > 0 ? (t[j] - med) / scale : 0.0;
    o.rejected[j] = std::abs(o.score[j]) > threshold;
    o.one_sided[j] = o.score[j] > threshold;
    o.rejected_count += o.rejected[j] ? 1 : 0;
    o.one_sided_count += o.one_sided[j] ? 1 : 0;
    if (!o.rejected[j]) kept.push_back(t[j]);
  }
  o.used = kept.size();
  o.retained = kept.size() == 1 ? Estimate{kept[0], kNaN} : mean_and_error(kept);
  return o;
}

// ---- the response stage -------------------------------------------------------------------------

ResponseSettings parse_response_settings(tool::ConfigNode& cfg) {
  ResponseSettings s;
  s.species = cfg.string("species", "");
  s.signal = cfg.choice("signal", {"B2", "U_L", "U_W", "U_T", "S_cube"}, "B2");
  cfg.reject_unless(s.signal == "B2", "main_axis", "unless \"signal\" is \"B2\" (it is the axis of B_2)");
  cfg.reject_unless(s.signal == "S_cube", "field_direction", "unless \"signal\" is \"S_cube\" (it is the cube order's reference)");
  s.order.main_axis = parse_body_axis(cfg, "main_axis", "auto", true);
  s.field_given = cfg.has("field_direction");
  if (s.field_given) {
    const Vec3 e = cfg.vec3("field_direction");
    if (!(e.norm() > 0)) cfg.fail("field_direction", "expected a non-zero direction vector");
    s.order.field_direction = e.normalized();
  }
  if (cfg.has("switch_on")) s.switch_on = cfg.number("switch_on");
  if (cfg.has("switch_off")) {
    s.switch_off = cfg.number("switch_off");
    if (!s.switch_on) cfg.fail("switch_off", "expected switch_on as well (or neither, to read the field_switches observable)");
    if (!(*s.switch_off > *s.switch_on)) cfg.fail("switch_off", "expected switch_off > switch_on");
  }
  s.cycle = static_cast<std::size_t>(cfg.non_negative_integer("cycle", 0));
  if (s.switch_on && s.cycle > 0) cfg.fail("cycle", "expected 0: cycles count the switch-ons of the field_switches observable, not given instants");
  s.parameters.smoothing_fraction = cfg.positive("smoothing_fraction", s.parameters.smoothing_fraction);
  if (!(s.parameters.smoothing_fraction < 1)) cfg.fail("smoothing_fraction", "expected a fraction of the segment length below 1");
  s.z_threshold = cfg.positive("outlier_threshold", s.z_threshold);
  return s;
}

ResponseAnalysis::ResponseAnalysis(ResponseSettings settings, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)) {}

SwitchCycle ResponseAnalysis::cycle_of(const Trajectory& t) const {
  SwitchCycle c;
  if (s_.switch_on) {
    c.on = *s_.switch_on;
    if (s_.switch_off) c.off = *s_.switch_off;
  } else {
    const auto it = t.observables.find("field_switches");
    if (it == t.observables.end())
      throw InputError(t.path, kSwitches, "no field_switches observable; give switch_on (and switch_off) in the configuration");
    c = switch_cycle_from_observable(it->second, s_.cycle, t.path);
  }
  if (!(c.on > t.time.front() && c.on < t.time.back()))
    throw InputError(s_.switch_on ? config_file_ : t.path, s_.switch_on ? "switch_on" : kSwitches,
                     "the switch-on at t = " + std::to_string(c.on) + " is not inside " + t.path + " (frames from t = " +
                         std::to_string(t.time.front()) + " to " + std::to_string(t.time.back()) + ")");
  if (!std::isnan(c.off) && !(c.off < t.time.back()))
    throw InputError(s_.switch_on ? config_file_ : t.path, s_.switch_on ? "switch_off" : kSwitches,
                     "the switch-off at t = " + std::to_string(c.off) + " is after the last frame of " + t.path);
  return c;
}

double ResponseAnalysis::signal_of(const FrameOrder& o) const {
  if (s_.signal == "U_T") return o.axis[0].order;
  if (s_.signal == "U_W") return o.axis[1].order;
  if (s_.signal == "U_L") return o.axis[2].order;
  if (s_.signal == "S_cube") return o.cube.total;
  return o.biaxial;
}

void ResponseAnalysis::accumulate(const Trajectory& t, int species_index) {
  const auto members = t.members(species_index);
  if (members.empty()) throw InputError(t.path, "/particles/all/species", "no particle of the selected species");
  const SwitchCycle c = cycle_of(t);
  if (times_.empty()) {
    // spec 50 §3.2 Decision: the main axis is the one whose U was largest before switching (first
    // replica, frames before the switch-on), kept for every replica.
    const std::size_t pre = static_cast<std::size_t>(std::lower_bound(t.time.begin(), t.time.end(), c.on) - t.time.begin());
    const int resolved = run_averaged_main_axis(t, members, 0, pre, &main_axis_order_);
    main_axis_ = s_.order.main_axis < 0 ? resolved : s_.order.main_axis;
  }
  OrderSettings o = s_.order;
  o.chains.reset();
  if (!s_.field_given && c.field) o.field_direction = *c.field;
  std::vector<double> sig(t.frames);
  for (std::size_t f = 0; f < t.frames; ++f) sig[f] = signal_of(frame_order(frame_rotations(t, f, members), o, main_axis_));
  paths_.push_back(t.path);
  times_.push_back(t.time);
  signals_.push_back(std::move(sig));
  cycles_.push_back(c);
}

ResponseResult ResponseAnalysis::compute() const {
  ResponseResult r;
  r.signal = s_.signal;
  r.main_axis = main_axis_;
  r.main_axis_order = main_axis_order_;
  r.paths = paths_;
  std::vector<double> on, off, off95;
  for (std::size_t k = 0; k < times_.size(); ++k) {
    r.replicas.push_back(response_times(times_[k], signals_[k], cycles_[k], s_.parameters));
    on.push_back(r.replicas.back().t_on);
    off.push_back(r.replicas.back().t_off);
    off95.push_back(r.replicas.back().t_off95);
  }
  r.on = reject_outliers(on, s_.z_threshold);
  r.off = reject_outliers(off, s_.z_threshold);
  r.off95 = reject_outliers(off95, s_.z_threshold);
  // mean curve against time since switch-on: the common grid is the mean shifted time stamp (spec 50 §0)
  if (!times_.empty()) {
    const std::size_t frames = times_[0].size();
    r.curve_time.assign(frames, 0.0);
    for (std::size_t k = 0; k < times_.size(); ++k)
      for (std::size_t f = 0; f < frames; ++f) r.curve_time[f] += (times_[k][f] - cycles_[k].on) / static_cast<double>(times_.size());
    CurveSamples samples;
    for (std::size_t k = 0; k < times_.size(); ++k) {
      std::vector<double> shifted(frames);
      for (std::size_t f = 0; f < frames; ++f) shifted[f] = times_[k][f] - cycles_[k].on;
      samples.add(interpolate_onto(shifted, signals_[k], r.curve_time));
    }
    r.curve = samples.mean();
    r.curve_se = samples.standard_error();
  }
  return r;
}

}  // namespace anisodyn::analysis
