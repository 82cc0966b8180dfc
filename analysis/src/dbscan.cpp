#include "anisodyn/analysis/dbscan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include "anisodyn/analysis/frame_window.hpp"
#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/interactions/dipolar_pair.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kUnvisited = -2;

/// The Eps-neighbourhood of every point (the point itself not listed), as compressed rows.
struct Neighbourhoods {
  std::vector<std::size_t> first, list;  // the neighbours of i are list[first[i] … first[i + 1] − 1]
  std::size_t size(std::size_t i) const { return first[i + 1] - first[i]; }
  auto begin(std::size_t i) const { return list.begin() + static_cast<std::ptrdiff_t>(first[i]); }
  auto end(std::size_t i) const { return list.begin() + static_cast<std::ptrdiff_t>(first[i + 1]); }
};

/// Pairs |p − q| ≤ eps, the test made on the given coordinates as the definition reads, among the
/// candidates of the shared pair search (pair_search.hpp), which reaches a little beyond Eps.
Neighbourhoods eps_neighbourhoods(const std::vector<Point2>& p, double eps) {
  const double eps2 = eps * eps;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& [i, j] : planar_candidate_pairs(p, eps * (1 + 1e-6))) {
    const double dx = p[j].x - p[i].x, dy = p[j].y - p[i].y;
    if (dx * dx + dy * dy <= eps2) pairs.emplace_back(i, j);
  }
  Neighbourhoods n;
  n.first.assign(p.size() + 1, 0);
  for (const auto& [i, j] : pairs) { ++n.first[i + 1]; ++n.first[j + 1]; }
  for (std::size_t i = 0; i < p.size(); ++i) n.first[i + 1] += n.first[i];
  n.list.resize(n.first.back());
  std::vector<std::size_t> next(n.first.begin(), n.first.end() - 1);
  for (const auto& [i, j] : pairs) { n.list[next[i]++] = j; n.list[next[j]++] = i; }
  return n;
}

/// βu of a (r_∥, r_⊥) point: r² = r_∥² + r_⊥² and Ê·r = r_∥ in the one pair energy of engine and
/// analyses (interactions/dipolar_pair.hpp).
double point_energy(const Point2& p, const DipolarBondRule& rule) {
  return dipolar_pair_energy(p.x * p.x + p.y * p.y, p.x, rule.gamma, rule.sigma);
}

}  // namespace

DbscanLabels dbscan(const std::vector<Point2>& points, double eps, std::size_t min_pts) {
  if (!(eps > 0)) throw InputError("", "eps", "DBSCAN needs a positive Eps");
  if (min_pts < 1) throw InputError("", "min_pts", "DBSCAN needs MinPts >= 1");
  DbscanLabels out;
  out.label.assign(points.size(), kUnvisited);
  if (points.empty()) return out;
  const Neighbourhoods near = eps_neighbourhoods(points, eps);
  // N_Eps counts the point itself (as R's dbscan does)
  auto is_core = [&](std::size_t i) { return near.size(i) + 1 >= min_pts; };
  std::vector<std::size_t> seeds;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (out.label[p] != kUnvisited) continue;
    if (!is_core(p)) {
      out.label[p] = kDbscanNoise;  // may still become a border point of a later cluster
      continue;
    }
    const int c = out.clusters++;
    out.label[p] = c;
    seeds.assign(near.begin(p), near.end(p));
    while (!seeds.empty()) {
      const std::size_t q = seeds.back();
      seeds.pop_back();
      if (out.label[q] == kDbscanNoise) out.label[q] = c;  // border point
      if (out.label[q] != kUnvisited) continue;
      out.label[q] = c;
      if (is_core(q)) seeds.insert(seeds.end(), near.begin(q), near.end(q));
    }
  }
  for (int l : out.label)
    if (l == kDbscanNoise) ++out.noise;
  return out;
}

std::vector<double> sorted_knn_distances(const std::vector<Point2>& points, std::size_t k) {
  std::vector<double> out;
  if (k == 0 || points.size() <= k) return out;
  std::vector<double> d2(points.size() - 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::size_t m = 0;
    for (std::size_t j = 0; j < points.size(); ++j)
      if (j != i) {
        const double dx = points[j].x - points[i].x, dy = points[j].y - points[i].y;
        d2[m++] = dx * dx + dy * dy;
      }
    std::nth_element(d2.begin(), d2.begin() + static_cast<std::ptrdiff_t>(k - 1), d2.end());
    out.push_back(std::sqrt(d2[k - 1]));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t knee_index(const std::vector<double>& d) {
  const std::size_t n = d.size();
  if (n < 3 || !(d.back() > d.front())) return n == 0 ? 0 : n - 1;
  std::size_t best = n - 1;
  double best_gap = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k) / static_cast<double>(n - 1);
    const double y = (d[k] - d.front()) / (d.back() - d.front());
    if (x - y > best_gap) { best_gap = x - y; best = k; }
  }
  return best;
}

DbscanCalibrationSettings parse_dbscan_settings(tool::ConfigNode& cfg) {
  DbscanCalibrationSettings s;
  s.species = cfg.string("species", "");
  s.rule = parse_dipolar_bond_rule(cfg, false);
  s.min_pts = static_cast<std::size_t>(cfg.positive_integer("min_pts", 10));
  if (cfg.has("eps")) s.eps = cfg.positive("eps");
  s.r_max = cfg.positive("r_max", 2.0 * s.rule.sigma);
  if (cfg.has("eps_factors")) {
    s.eps_factors = cfg.numbers("eps_factors");
    if (s.eps_factors.empty()) cfg.fail("eps_factors", "expected at least one factor");
    for (double f : s.eps_factors)
      if (!(f > 0)) cfg.fail("eps_factors", "expected positive factors");
  }
  refuse_frame_key(cfg, "t_min");
  return s;
}

std::vector<Point2> neighbour_separation_points(const std::vector<Vec3>& positions, const Box& box,
                                                const DbscanCalibrationSettings& s) {
  // A neighbour farther than √2 r_max cannot give r_∥, r_⊥ ≤ r_max, so the search stops there.
  const double reach = std::sqrt(2.0) * s.r_max * (1 + 1e-9);
  const std::size_t n = positions.size();
  struct Near {
    double r2 = std::numeric_limits<double>::infinity();
    std::size_t j = 0;
    Vec3 d = Vec3::Zero();  // r_j − r_i
  };
  std::vector<std::array<Near, 2>> nearest(n);
  auto offer = [&](std::size_t i, std::size_t j, const Vec3& d) {
    const double r2 = d.squaredNorm();
    auto& a = nearest[i];
    if (r2 < a[0].r2) { a[1] = a[0]; a[0] = {r2, j, d}; }
    else if (r2 < a[1].r2) a[1] = {r2, j, d};
  };
  for (const ClosePair& p : close_pairs(positions, box, reach)) {
    offer(p.i, p.j, p.d);
    offer(p.j, p.i, -p.d);
  }
  std::set<std::pair<std::size_t, std::size_t>> seen;  // duplicate pairs (i's neighbour j and j's neighbour i)
  std::vector<Point2> points;
  for (std::size_t i = 0; i < n; ++i)
    for (const Near& nb : nearest[i]) {
      if (!std::isfinite(nb.r2)) continue;
      if (!seen.insert({std::min(i, nb.j), std::max(i, nb.j)}).second) continue;
      const double par = std::abs(nb.d.dot(s.rule.field));
      const double perp = std::sqrt(std::max(0.0, nb.d.squaredNorm() - par * par));
      if (par <= s.r_max && perp <= s.r_max) points.push_back({par, perp});
    }
  return points;
}

BondCalibration calibrate_bond_threshold(const std::vector<Point2>& points, double eps, const DbscanCalibrationSettings& s) {
  BondCalibration b;
  b.eps = eps;
  b.bu_max = kNaN;
  if (points.empty() || !(eps > 0)) return b;
  const DbscanLabels labels = dbscan(points, eps, s.min_pts);
  b.clusters = labels.clusters;
  b.noise = labels.noise;
  if (labels.clusters == 0) return b;
  // the cluster whose centroid is nearest the stacked-cube minimum (σ, 0) (Decision)
  std::vector<double> sx(static_cast<std::size_t>(labels.clusters), 0.0), sy(sx), count(sx);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (labels.label[k] >= 0) {
      const auto c = static_cast<std::size_t>(labels.label[k]);
      sx[c] += points[k].x; sy[c] += points[k].y; count[c] += 1;
    }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < sx.size(); ++c) {
    const double dx = sx[c] / count[c] - s.rule.sigma, dy = sy[c] / count[c];
    if (dx * dx + dy * dy < best) { best = dx * dx + dy * dy; b.cluster = static_cast<int>(c); }
  }
  b.bu_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < points.size(); ++k)
    if (labels.label[k] == b.cluster) {
      b.bu_max = std::max(b.bu_max, point_energy(points[k], s.rule));
      ++b.cluster_points;
    }
  return b;
}

DbscanCalibration::DbscanCalibration(DbscanCalibrationSettings settings, std::string config_file)
    : s_(std::move(settings)), config_file_(std::move(config_file)) {
  if (!(s_.rule.gamma > 0)) throw InputError(config_file_, "gamma", "the dipolar coupling must be positive");
  if (s_.min_pts < 1) throw InputError(config_file_, "min_pts", "expected MinPts >= 1");
  if (s_.eps && !(*s_.eps > 0)) throw InputError(config_file_, "eps", "expected a positive Eps");
  if (!(s_.r_max > 0)) throw InputError(config_file_, "r_max", "expected a positive r_max");
  if (s_.eps_factors.empty()) throw InputError(config_file_, "eps_factors", "expected at least one factor");
  if (!(s_.rule.field.norm() > 0)) throw InputError(config_file_, "field_direction", "expected a non-zero direction");
  s_.rule.field.normalize();
}

void DbscanCalibration::accumulate(const Trajectory& t, int species_index) {
  const std::vector<std::size_t> members = t.members(species_index);
  if (members.size() < 2) throw InputError(t.path, "", "fewer than two particles of the selected species");
  std::vector<Vec3> r(members.size());
  for (std::size_t f = 0; f < t.frames; ++f) {
    for (std::size_t m = 0; m < members.size(); ++m) r[m] = t.pos(f, members[m]);
    const std::vector<Point2> points = neighbour_separation_points(r, Box(t.box_edges(f)), s_);
    CalibrationConfiguration c;
    c.replica = replicas_seen_;
    c.frame = t.file_frame(f);
    c.time = t.time[f];
    c.points = points.size();
    if (s_.eps) {
      c.base_eps = *s_.eps;
    } else {
      const std::vector<double> knn = sorted_knn_distances(points, s_.min_pts);
      c.base_eps = knn.empty() ? kNaN : knn[knee_index(knn)];
    }
    for (double factor : s_.eps_factors) c.per_factor.push_back(calibrate_bond_threshold(points, factor * c.base_eps, s_));
    configs_.push_back(std::move(c));
  }
  ++replicas_seen_;
}

DbscanCalibrationResult DbscanCalibration::compute() const {
  DbscanCalibrationResult r;
  r.eps_factors = s_.eps_factors;
  r.configurations = configs_;
  std::vector<double> eps;
  for (const auto& c : configs_)
    if (std::isfinite(c.base_eps)) eps.push_back(c.base_eps);
  r.base_eps = mean_and_error(eps);
  for (std::size_t k = 0; k < s_.eps_factors.size(); ++k) {
    std::vector<double> v;
    for (const auto& c : configs_)
      if (std::isfinite(c.per_factor[k].bu_max)) v.push_back(c.per_factor[k].bu_max);
    r.bu_max.push_back(mean_and_error(v));
    r.used.push_back(v.size());
  }
  return r;
}

}  // namespace anisodyn::analysis
