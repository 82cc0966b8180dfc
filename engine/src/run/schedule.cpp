#include "anisodyn/run/schedule.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace anisodyn::run {

namespace {

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

FieldSegment parse_segment(tool::ConfigNode& seg, const StepUnit& unit) {
  FieldSegment s;
  s.field_on = seg.choice("field", {"on", "off"}) == "on";
  if (seg.has(unit.plural) == seg.has("time"))
    seg.fail("", "expected exactly one of '" + unit.plural + "' or 'time'" + unit.time_note + " for the segment's length");
  if (seg.has(unit.plural)) {
    s.unit = FieldSegment::Unit::Steps;
    s.length = static_cast<double>(seg.positive_integer(unit.plural));
  } else {
    s.unit = FieldSegment::Unit::Time;
    s.length = seg.positive("time");
  }
  return s;
}

/// `switches` (absolute instants, strictly increasing, one unit) → segments; the run's end comes
/// from the run length at the top level.
std::vector<FieldSegment> parse_switches(tool::ConfigNode& schedule, const StepUnit& unit, bool initially_on,
                                         const FieldSegment& end) {
  std::vector<FieldSegment> out;
  bool on = initially_on;
  double last = 0.0;
  std::optional<FieldSegment::Unit> seen;
  auto nodes = schedule.objects("switches");
  for (auto& sw : nodes) {
    const bool by_step = sw.has(unit.singular);
    if (by_step == sw.has("time"))
      sw.fail("", "expected exactly one of '" + unit.singular + "' or 'time' (the switch instant)");
    const FieldSegment::Unit u = by_step ? FieldSegment::Unit::Steps : FieldSegment::Unit::Time;
    const double at = by_step ? static_cast<double>(sw.positive_integer(unit.singular)) : sw.positive("time");
    if (seen && *seen != u) sw.fail("", "expected every switch in the same unit (all '" + unit.singular + "' or all 'time')");
    seen = u;
    if (at <= last)
      sw.fail(by_step ? unit.singular : "time", "expected switch instants in increasing order (after " + format_number(last) + ")");
    const bool next = sw.choice("field", {"on", "off"}) == "on";
    out.push_back(FieldSegment{on, u, true, at});
    on = next;
    last = at;
  }
  if (seen && end.unit == *seen && end.length <= last)
    schedule.fail("switches", "expected every switch before the end of the run (" + format_number(end.length) + ")");
  FieldSegment tail = end;
  tail.field_on = on;
  tail.absolute = true;
  out.push_back(tail);
  return out;
}

}  // namespace

bool schedule_has_segments(const tool::ConfigNode& cfg) {
  return cfg.has("schedule") && cfg.raw().at("schedule").is_object() && cfg.raw().at("schedule").contains("segments");
}

std::vector<FieldSegment> parse_schedule(tool::ConfigNode& cfg, const StepUnit& unit, bool initially_on) {
  std::vector<FieldSegment> segments;
  auto schedule = cfg.optional_object("schedule");
  if (schedule && schedule->has("segments")) {
    if (cfg.has(unit.plural) || cfg.has("time"))
      cfg.fail(cfg.has(unit.plural) ? unit.plural : "time", "expected no run length when schedule.segments gives it");
    if (auto field = cfg.optional_object("field"))
      field->reject_unless(false, "initially", "with schedule.segments (the first segment's 'field' says how the run starts)");
    const std::int64_t repeat = schedule->positive_integer("repeat", 1);
    std::vector<FieldSegment> once;
    for (auto& seg : schedule->objects("segments")) once.push_back(parse_segment(seg, unit));
    if (once.empty()) schedule->fail("segments", "expected at least one segment");
    for (std::int64_t r = 0; r < repeat; ++r) segments.insert(segments.end(), once.begin(), once.end());
    if (schedule->has("switches")) schedule->fail("switches", "expected either 'segments' or 'switches', not both");
    return segments;
  }
  if (cfg.has(unit.plural) == cfg.has("time"))
    cfg.fail(unit.plural, "expected exactly one run length: '" + unit.plural + "' or 'time'" + unit.time_note);
  FieldSegment end;
  if (cfg.has(unit.plural))
    end = FieldSegment{initially_on, FieldSegment::Unit::Steps, true, static_cast<double>(cfg.positive_integer(unit.plural))};
  else
    end = FieldSegment{initially_on, FieldSegment::Unit::Time, true, cfg.positive("time")};
  if (schedule) schedule->reject_unless(false, "repeat", "without schedule.segments (it repeats their list)");
  if (schedule && schedule->has("switches")) return parse_switches(*schedule, unit, initially_on, end);
  return {end};
}

nlohmann::json SchedulePosition::to_json() const {
  return {{"segment", segment}, {"segment_started", segment_started}, {"segment_start", segment_start}, {"segment_end", segment_end}};
}

SchedulePosition SchedulePosition::from_json(const nlohmann::json& j) {
  SchedulePosition p;
  p.segment = j.at("segment").get<std::size_t>();
  p.segment_started = j.at("segment_started").get<bool>();
  p.segment_start = j.at("segment_start").get<double>();
  p.segment_end = j.at("segment_end").get<double>();
  return p;
}

void ScheduleClock::start(std::int64_t step, double time) {
  const FieldSegment& seg = current();
  pos_.segment_start = now(step, time);
  pos_.segment_end = seg.absolute ? seg.length : pos_.segment_start + seg.length;
  pos_.segment_started = true;
}

bool ScheduleClock::segment_done(std::int64_t step, double time) const { return now(step, time) >= pos_.segment_end; }

bool ScheduleClock::next() {
  if (pos_.segment + 1 >= segments_.size()) return false;
  ++pos_.segment;
  pos_.segment_started = false;
  return true;
}

double ScheduleClock::fraction(std::int64_t step, double time) const {
  const double span = pos_.segment_end - pos_.segment_start;
  const double within = span > 0.0 ? std::clamp((now(step, time) - pos_.segment_start) / span, 0.0, 1.0) : 1.0;
  return (static_cast<double>(pos_.segment) + within) / static_cast<double>(segments_.size());
}

}  // namespace anisodyn::run
