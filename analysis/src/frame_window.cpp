#include "anisodyn/analysis/frame_window.hpp"

#include <cmath>
#include <sstream>

namespace anisodyn::analysis {

namespace {

std::string number_text(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

}  // namespace

FrameWindow parse_frame_window(tool::ConfigNode& cfg) {
  FrameWindow w;
  w.config_file = cfg.file();
  auto node = cfg.optional_object("window");
  if (!node) return w;
  w.given = true;
  if (node->has("from")) w.from = node->number("from");
  if (node->has("to")) w.to = node->number("to");
  w.stride = static_cast<std::size_t>(node->positive_integer("stride", 1));
  if (w.from && w.to && !(*w.to > *w.from))
    node->fail("to", "expected a window end after its start (from = " + number_text(*w.from) + ")");
  return w;
}

void refuse_frame_key(tool::ConfigNode& cfg, const std::string& key) {
  if (cfg.has(key))
    cfg.fail(key, "no '" + key + "' key: choose the analysed frames by time with \"window\": {\"from\": t0, \"to\": t1, \"stride\": k}");
}

bool FrameWindow::contains(double t) const {
  if (from && t < *from - 1e-9 * std::abs(*from)) return false;
  if (to && t > *to + 1e-9 * std::abs(*to)) return false;
  return true;
}

io::FrameSlice FrameWindow::select(const std::vector<double>& time) const {
  if (!given) return {0, time.size(), 1};
  std::size_t first = 0;
  while (first < time.size() && !contains(time[first])) ++first;
  std::size_t end = first;
  while (end < time.size() && contains(time[end])) ++end;
  const std::size_t span = end - first;
  return {first, span == 0 ? 0 : (span - 1) / stride + 1, stride};
}

std::string FrameWindow::text() const {
  std::string out = "window {";
  if (from) out += "from: " + number_text(*from) + ", ";
  if (to) out += "to: " + number_text(*to) + ", ";
  return out + "stride: " + std::to_string(stride) + "}";
}

std::string FrameWindow::too_few_frames(const io::FrameSlice& frames, const std::vector<double>& time, const std::string& path,
                                        std::size_t needed) const {
  std::string span = time.empty() ? "no frames" : std::to_string(time.size()) + " frames at t = " + number_text(time.front()) +
                                                       " … " + number_text(time.back());
  return text() + " selects " + std::to_string(frames.count) + " frame(s) of " + path + " (it has " + span +
         "); this stage needs at least " + std::to_string(needed);
}

nlohmann::json FrameWindow::record(const io::FrameSlice& frames, const std::vector<double>& time) const {
  nlohmann::json r = {{"from", from ? nlohmann::json(*from) : nlohmann::json(nullptr)},
                      {"to", to ? nlohmann::json(*to) : nlohmann::json(nullptr)},
                      {"stride", stride},
                      {"frames", frames.count},
                      {"time_grid", "mean time stamp of each frame over the replicas (spec 50 section 0)"}};
  if (frames.count > 0) {
    const std::size_t last = frames.frame(frames.count - 1);
    r["first_frame"] = frames.first;
    r["last_frame"] = last;
    r["first_time"] = time[frames.first];
    r["last_time"] = time[last];
  }
  return r;
}

}  // namespace anisodyn::analysis
