#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/Eigenvalues>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/core/statistics.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A unit vector perpendicular to n (for a degenerate biaxial frame).
Vec3 any_perpendicular(const Vec3& n) {
  const Vec3 trial = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (trial - trial.dot(n) * n).normalized();
}
}  // namespace

int parse_body_axis(tool::ConfigNode& cfg, const std::string& key, const std::string& fallback, bool allow_auto) {
  return io::choose_body_axis(cfg, key, fallback, true, allow_auto ? std::vector<std::string>{"auto"} : std::vector<std::string>{});
}

const char* axis_letter(int k) { return k >= 0 && k < 3 ? body_axis_name(k) : "auto"; }

AxisOrder axis_order(const Mat3& q) {
  const UniaxialOrder u = uniaxial_order(q);
  AxisOrder a;
  a.q = q;
  a.eigenvalues = u.eigenvalues;
  a.order = u.order;
  a.director = u.director;
  return a;
}

std::array<Mat3, 3> axis_q_tensors(const std::vector<Mat3>& rotations) {
  std::array<Mat3, 3> q{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
  if (rotations.empty()) return q;
  for (const Mat3& r : rotations)
    for (int k = 0; k < 3; ++k) q[static_cast<std::size_t>(k)] += r.col(k) * r.col(k).transpose();
  const double n = static_cast<double>(rotations.size());
  for (auto& m : q) m = (3.0 * m / n - Mat3::Identity()) / 2.0;
  return q;
}

int largest_order_axis(const std::array<Mat3, 3>& q) {
  int best = 0;
  double best_u = uniaxial_order(q[0]).order;
  for (int k = 1; k < 3; ++k) {
    const double u = uniaxial_order(q[static_cast<std::size_t>(k)]).order;
    if (u > best_u) { best = k; best_u = u; }
  }
  return best;
}

double biaxial_order(const std::array<Mat3, 3>& q, int main_axis) {
  const auto K = static_cast<std::size_t>(main_axis);
  const std::size_t P = (K + 2) % 3, R = (K + 1) % 3;
  const Vec3 n = uniaxial_order(q[K]).director;
  Vec3 p = uniaxial_order(q[P]).director;
  p -= p.dot(n) * n;
  p = p.norm() > 1e-12 ? Vec3(p.normalized()) : any_perpendicular(n);
  const Vec3 r = n.cross(p);
  const Mat3& qp = q[P];
  const Mat3& qr = q[R];
  return (p.dot(qp * p) + r.dot(qr * r) - p.dot(qr * p) - r.dot(qp * r)) / 3.0;
}

Mat3 rod_order_tensor(const std::vector<Mat3>& rotations, int axis) {
  Mat3 s = Mat3::Zero();
  for (const Mat3& r : rotations) s += r.col(axis) * r.col(axis).transpose();
  return rotations.empty() ? s : Mat3(s / static_cast<double>(rotations.size()));
}

double max_squared_projection(const Mat3& rotation, const Vec3& field) {
  const Vec3 c = rotation.transpose() * field;  // Ê·ê_k for k = 0, 1, 2
  return c.cwiseAbs2().maxCoeff();
}

double cube_order(const Mat3& rotation, const Vec3& field) {
  const double s3 = std::sqrt(3.0);
  return (M_PI * (3.0 * max_squared_projection(rotation, field) - 1.0) - 2.0 * s3) / (2.0 * M_PI - 2.0 * s3);
}

CubeOrder cube_order_average(const std::vector<Mat3>& rotations, const Vec3& field, const std::vector<char>& in_chain) {
  CubeOrder out;
  if (rotations.empty()) return out;
  const bool split = !in_chain.empty();
  if (split && in_chain.size() != rotations.size()) throw RuntimeFailure("cube_order_average: chain mask size differs from the particle count");
  double tot = 0, chain = 0, free = 0, cos2 = 0;
  std::size_t n_chain = 0;
  for (std::size_t i = 0; i < rotations.size(); ++i) {
    const double c2 = max_squared_projection(rotations[i], field);
    const double s = cube_order(rotations[i], field);
    tot += s;
    cos2 += c2;
    if (split && in_chain[i]) { chain += s; ++n_chain; }
    else if (split) free += s;
  }
  const double n = static_cast<double>(rotations.size());
  out.total = tot / n;
  out.max_cos2 = cos2 / n;
  if (split) {
    out.chain_fraction = static_cast<double>(n_chain) / n;
    if (n_chain > 0) out.chain = chain / static_cast<double>(n_chain);
    if (n_chain < rotations.size()) out.free = free / static_cast<double>(rotations.size() - n_chain);
  }
  return out;
}

FrameOrder frame_order(const std::vector<Mat3>& rotations, const OrderSettings& s, int main_axis, const std::vector<char>& in_chain) {
  FrameOrder out;
  const auto q = axis_q_tensors(rotations);
  for (std::size_t k = 0; k < 3; ++k) out.axis[k] = axis_order(q[k]);
  out.nematic_axis = 0;
  for (int k = 1; k < 3; ++k)
    if (out.axis[static_cast<std::size_t>(k)].order > out.axis[static_cast<std::size_t>(out.nematic_axis)].order) out.nematic_axis = k;
  out.nematic_order = out.axis[static_cast<std::size_t>(out.nematic_axis)].order;
  out.director = out.axis[static_cast<std::size_t>(out.nematic_axis)].director;
  out.main_axis = main_axis < 0 ? out.nematic_axis : main_axis;
  out.biaxial = biaxial_order(q, out.main_axis);
  out.rod_tensor = rod_order_tensor(rotations, s.rod_axis);
  out.rod_order = Eigen::SelfAdjointEigenSolver<Mat3>(out.rod_tensor, Eigen::EigenvaluesOnly).eigenvalues()[2];
  out.cube = cube_order_average(rotations, s.field_direction, in_chain);
  return out;
}

std::vector<Mat3> frame_rotations(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members) {
  std::vector<Mat3> r;
  r.reserve(members.size());
  for (std::size_t i : members) r.push_back(t.quat(f, i).normalized().toRotationMatrix());
  return r;
}

std::vector<Vec3> frame_positions(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members) {
  std::vector<Vec3> p;
  p.reserve(members.size());
  for (std::size_t i : members) p.push_back(t.pos(f, i));
  return p;
}

FrameOrder trajectory_frame_order(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members,
                                  const OrderSettings& s, int main_axis) {
  std::vector<char> mask;
  if (s.chains) mask = dipolar_chain_mask(frame_positions(t, f, members), Box(t.box_edges(f)), *s.chains);
  return frame_order(frame_rotations(t, f, members), s, main_axis, mask);
}

int run_averaged_main_axis(const Trajectory& t, const std::vector<std::size_t>& members, std::size_t first, std::size_t last,
                           Vec3* order) {
  last = std::min(last, t.frames);
  if (first >= last) { first = 0; last = t.frames; }
  std::array<Mat3, 3> q{Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
  for (std::size_t f = first; f < last; ++f) {
    const auto qf = axis_q_tensors(frame_rotations(t, f, members));
    for (std::size_t k = 0; k < 3; ++k) q[k] += qf[k] / static_cast<double>(last - first);
  }
  if (order)
    for (std::size_t k = 0; k < 3; ++k) (*order)[static_cast<int>(k)] = uniaxial_order(q[k]).order;
  return largest_order_axis(q);
}

std::vector<double> interpolate_onto(const std::vector<double>& time, const std::vector<double>& value,
                                     const std::vector<double>& grid) {
  std::vector<double> out(grid.size(), kNaN);
  if (time.empty()) return out;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const double x = grid[g];
    if (x <= time.front()) { out[g] = value.front(); continue; }
    if (x >= time.back()) { out[g] = value.back(); continue; }
    const auto it = std::upper_bound(time.begin(), time.end(), x);
    const std::size_t j = static_cast<std::size_t>(it - time.begin());
    const double w = (x - time[j - 1]) / (time[j] - time[j - 1]);
    out[g] = (1 - w) * value[j - 1] + w * value[j];
  }
  return out;
}

// ---- the order stage -------------------------------------------------------------------------------

OrderStageSettings parse_order_settings(tool::ConfigNode& cfg) {
  OrderStageSettings s;
  s.species = cfg.string("species", "");
  if (cfg.has("observables")) {
    s.observables = cfg.strings("observables");
    for (const auto& o : s.observables)
      if (o != "U" && o != "B2" && o != "S_rod" && o != "S_cube")
        cfg.fail("observables", "expected a list of \"U\", \"B2\", \"S_rod\", \"S_cube\" (got \"" + o + "\")");
  }
  const auto wanted = [&](const char* o) { return std::find(s.observables.begin(), s.observables.end(), o) != s.observables.end(); };
  cfg.reject_unless(wanted("S_rod"), "rod_axis", "without S_rod in observables");
  for (const char* key : {"field_direction", "chain_threshold"})
    cfg.reject_unless(wanted("S_cube"), key, "without S_cube in observables (it shapes the cube order)");
  s.order.main_axis = parse_body_axis(cfg, "main_axis", "auto", true);
  s.order.rod_axis = parse_body_axis(cfg, "rod_axis", "L", false);
  const Vec3 e = cfg.vec3("field_direction", Vec3::UnitZ());
  if (!(e.norm() > 0)) cfg.fail("field_direction", "expected a non-zero direction vector");
  s.order.field_direction = e.normalized();
  if (auto c = cfg.optional_object("chain_threshold")) {
    DipolarBondRule rule;
    rule.field = s.order.field_direction;
    rule.gamma = c->positive("gamma");
    rule.sigma = c->positive("sigma", 1.0);
    rule.bu_max = c->number("bu_max", -3.20);
    if (!(rule.bu_max < 0)) c->fail("bu_max", "expected a negative energy threshold (the bond rule is βu_ij < bu_max)");
    s.order.chains = rule;
  }
  s.average_from = cfg.number("average_from", -INFINITY);
  return s;
}

const OrderSeries& OrderResult::get(const std::string& name) const {
  for (const auto& s : series)
    if (s.name == name) return s;
  throw RuntimeFailure("no order series " + name);
}

OrderAnalysis::OrderAnalysis(OrderStageSettings settings, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)) {}

std::vector<std::string> OrderAnalysis::names() const {
  std::vector<std::string> n{"U_T", "U_W", "U_L", "U", "B2", "S_rod", "S_cube"};
  if (s_.order.chains) n.insert(n.end(), {"S_cube_chain", "S_cube_free", "chain_fraction"});
  return n;
}

void OrderAnalysis::accumulate(const Trajectory& t, int species_index) {
  const auto members = t.members(species_index);
  if (members.empty()) throw InputError(t.path, "/particles/all/species", "no particle of the selected species");
  if (!t.orientation.size()) throw RuntimeFailure("OrderAnalysis needs orientations");
  if (s_.order.chains && t.position.empty()) throw RuntimeFailure("OrderAnalysis needs positions for the chain rule");
  if (times_.empty()) {
    // The main axis K is fixed once, from the first replica, so that every replica's B_2 is the
    // same quantity (spec 50 §3.2: record the choice).
    main_axis_ = s_.order.main_axis;
    const int resolved = run_averaged_main_axis(t, members, 0, t.frames, &main_axis_order_);
    if (main_axis_ < 0) main_axis_ = resolved;
    particles_ = members.size();
  }
  const auto n = names();
  std::vector<std::vector<double>> v(n.size(), std::vector<double>(t.frames, kNaN));
  for (std::size_t f = 0; f < t.frames; ++f) {
    const FrameOrder o = trajectory_frame_order(t, f, members, s_.order, main_axis_);
    const double row[] = {o.axis[0].order, o.axis[1].order, o.axis[2].order, o.nematic_order, o.biaxial, o.rod_order,
                          o.cube.total, o.cube.chain, o.cube.free, o.cube.chain_fraction};
    for (std::size_t k = 0; k < n.size(); ++k) v[k][f] = row[k];
  }
  times_.push_back(t.time);
  values_.push_back(std::move(v));
}

namespace {
struct SeriesInfo {
  const char* units;
  const char* definition;
};

SeriesInfo series_info(const std::string& name) {
  if (name == "U_T" || name == "U_W" || name == "U_L")
    return {"1", "spec 50 C1: largest eigenvalue of Q^{kk} = (1/2N) sum_i (3 e_k,i e_k,i - I) for body axis k"};
  if (name == "U") return {"1", "spec 50 C1: max_k U_k (the nematic director is the eigenvector of this axis)"};
  if (name == "B2") return {"1", "spec 50 C2: B_2,K = (1/3)(p.Q^PP.p + r.Q^RR.r - p.Q^RR.p - r.Q^PP.r), main axis K"};
  if (name == "S_rod") return {"1", "spec 50 C3: largest eigenvalue of S = (1/N) sum_n u_n u_n (trace 1) of the rod axis"};
  if (name == "S_cube") return {"1", "spec 50 C4: S^(tot) = mean_i [pi (3 max_k (E.e_k,i)^2 - 1) - 2 sqrt 3]/(2 pi - 2 sqrt 3)"};
  if (name == "S_cube_chain") return {"1", "spec 50 C4: S^(c), mean S_i over cubes in dipolar clusters of size >= 2 (spec 50 E2 bond rule)"};
  if (name == "S_cube_free") return {"1", "spec 50 C4: S^(free), mean S_i over free cubes (cluster size 1, spec 50 E2 bond rule)"};
  return {"1", "fraction of the particles in dipolar clusters of size >= 2 (spec 50 E2: beta u_ij < beta u_max)"};
}
}  // namespace

OrderResult OrderAnalysis::compute(const std::vector<double>& common_time) const {
  OrderResult r;
  r.time = common_time;
  r.main_axis = main_axis_;
  r.main_axis_order = main_axis_order_;
  r.particles = particles_;
  r.replicas = times_.size();
  const auto n = names();
  for (std::size_t k = 0; k < n.size(); ++k) {
    OrderSeries s;
    s.name = n[k];
    const SeriesInfo info = series_info(n[k]);
    s.units = info.units;
    s.definition = info.definition;
    CurveSamples curves;
    std::vector<double> averages;
    for (std::size_t rep = 0; rep < times_.size(); ++rep) {
      curves.add(interpolate_onto(times_[rep], values_[rep][k], common_time));
      std::vector<double> window;
      for (std::size_t f = 0; f < times_[rep].size(); ++f)
        if (times_[rep][f] >= s_.average_from && !std::isnan(values_[rep][k][f])) window.push_back(values_[rep][k][f]);
      if (rep == 0) r.averaged_frames = window.size();
      const MeanError b = block_average(window);
      s.replica_average.push_back(window.empty() ? kNaN : b.mean);
      s.replica_block_error.push_back(window.empty() ? kNaN : b.error);
    }
    s.mean = curves.mean();
    s.error = curves.standard_error();
    if (s.replica_average.size() >= 2) s.run_average = mean_and_error(s.replica_average);
    else if (!s.replica_average.empty()) s.run_average = {s.replica_average[0], s.replica_block_error[0]};
    r.series.push_back(std::move(s));
  }
  if (r.averaged_frames == 0 && !times_.empty())
    throw InputError(config_file_, "average_from", "no frame at or after average_from = " + std::to_string(s_.average_from));
  r.isotropic_baseline = isotropic_order_baseline(particles_);
  r.largest_eigenvalue = std::max({r.get("U_T").run_average.value, r.get("U_W").run_average.value, r.get("U_L").run_average.value});
  r.nematic = r.largest_eigenvalue > kNematicThreshold;
  return r;
}

}  // namespace anisodyn::analysis
