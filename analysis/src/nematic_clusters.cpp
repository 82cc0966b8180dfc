#include "anisodyn/analysis/nematic_clusters.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "anisodyn/analysis/frame_window.hpp"
#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/analysis/union_find.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string text(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}
}  // namespace

namespace {
struct SettingsProblem {
  std::string key, problem, value;  // value: for the library-level message (ConfigNode::fail adds its own)
};

SettingsProblem settings_problem(const NematicClusterSettings& s) {
  if (!(s.k1 > 0 && s.k1 <= 1)) return {"K1", "expected K1 in (0, 1] (a bound on |e_i.e_j|)", text(s.k1)};
  if (!(s.k2 > -0.5 && s.k2 <= 1)) return {"K2", "expected K2 in (-1/2, 1] (a bound on the order parameter U_local)", text(s.k2)};
  if (!(s.k_par > 0) || !std::isfinite(s.k_par)) return {"K_par", "expected a positive finite length", text(s.k_par)};
  if (!(s.k_perp > 0) || !std::isfinite(s.k_perp)) return {"K_perp", "expected a positive finite length", text(s.k_perp)};
  if (s.axis < 0 || s.axis > 2) return {"axis", "expected a body axis T, W or L", ""};
  if (s.max_passes < 1) return {"max_passes", "expected at least one pass", ""};
  if (s.cos_bins < 1) return {"cos_bins", "expected at least one bin", ""};
  return {};
}
}  // namespace

void check_nematic_cluster_settings(const NematicClusterSettings& s, const std::string& config_file) {
  const SettingsProblem p = settings_problem(s);
  if (!p.key.empty()) throw InputError(config_file, p.key, p.problem + (p.value.empty() ? "" : ", got " + p.value));
}

NematicClusterSettings parse_nematic_cluster_settings(tool::ConfigNode& cfg) {
  NematicClusterSettings s;
  s.species = cfg.string("species", "");
  s.axis = io::require_body_axis(cfg, "axis", false);
  s.k1 = cfg.number("K1", s.k1);
  s.k2 = cfg.number("K2", s.k2);
  s.k_par = cfg.positive("K_par");
  s.k_perp = cfg.positive("K_perp");
  s.cos_bins = static_cast<std::size_t>(cfg.positive_integer("cos_bins", 20));
  refuse_frame_key(cfg, "t_min");
  const SettingsProblem p = settings_problem(s);
  if (!p.key.empty()) cfg.fail(p.key, p.problem);
  return s;
}

namespace {

struct Candidate {
  std::size_t i, j;
  Vec3 d;  // r_j − r_i, minimum image
  bool active = true;
};

bool inside_slab(const Vec3& d, const Vec3& n, const NematicClusterSettings& s) {
  const double par = d.dot(n);
  const double perp = (d - par * n).norm();
  return std::abs(par) < s.k_par && perp < s.k_perp;
}

/// Step 1: criteria 1 and 3 with the pair director.
std::vector<Candidate> candidate_bonds(const std::vector<Vec3>& r, const std::vector<Vec3>& e, const Box& box,
                                       const NematicClusterSettings& s) {
  std::vector<Candidate> out;
  const double reach = std::hypot(s.k_par, s.k_perp);  // |r| < √(K_∥² + K_⊥²) whatever the director
  for (const ClosePair& p : close_pairs(r, box, reach)) {
    const double c = e[p.i].dot(e[p.j]);
    if (!(std::abs(c) > s.k1)) continue;
    const Vec3 n = (e[p.i] + (c >= 0 ? 1.0 : -1.0) * e[p.j]).normalized();
    if (inside_slab(p.d, n, s)) out.push_back({p.i, p.j, p.d});
  }
  return out;
}

UniaxialOrder local_order(const std::vector<std::size_t>& members, const std::vector<Vec3>& e) {
  std::vector<Vec3> axes;
  axes.reserve(members.size());
  for (std::size_t m : members) axes.push_back(e[m]);
  return uniaxial_order(q_tensor(axes));
}

Components active_components(std::size_t n, const std::vector<Candidate>& bonds) {
  std::vector<Bond> b;
  for (const auto& c : bonds)
    if (c.active) b.emplace_back(c.i, c.j);
  return connected_components(n, b);
}

}  // namespace

NematicClustering nematic_clusters(const std::vector<Vec3>& positions, const std::vector<Vec3>& axes, const Box& box,
                                   const NematicClusterSettings& s) {
  check_nematic_cluster_settings(s);
  if (positions.size() != axes.size()) throw InputError("nematic_clusters: positions and axes differ in length");
  const std::size_t n = positions.size();
  std::vector<Vec3> e(n);
  for (std::size_t i = 0; i < n; ++i) e[i] = axes[i].normalized();
  std::vector<Candidate> bonds = candidate_bonds(positions, e, box, s);
  std::vector<std::vector<std::size_t>> bonds_of(n);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    bonds_of[bonds[b].i].push_back(b);
    bonds_of[bonds[b].j].push_back(b);
  }

  NematicClustering out;
  out.converged = false;
  for (int pass = 1; pass <= s.max_passes; ++pass) {
    out.passes = pass;
    bool changed = false;
    // steps 3–4: bonds must satisfy criterion 3 along their component's director
    Components c = active_components(n, bonds);
    std::vector<Vec3> director(c.count(), Vec3::Zero());
    const auto groups = c.members();
    for (std::size_t k = 0; k < c.count(); ++k)
      if (groups[k].size() >= 2) director[k] = local_order(groups[k], e).director;
    for (auto& b : bonds)
      if (b.active && !inside_slab(b.d, director[c.label[b.i]], s)) {
        b.active = false;
        changed = true;
      }
    // step 5: peel the least aligned member while U_local ≤ K2
    c = active_components(n, bonds);
    for (auto group : c.members()) {
      while (group.size() >= 2) {
        const UniaxialOrder u = local_order(group, e);
        if (u.order > s.k2) break;
        const auto worst = std::min_element(group.begin(), group.end(), [&](std::size_t a, std::size_t b) {
          return std::abs(e[a].dot(u.director)) < std::abs(e[b].dot(u.director));
        });
        for (std::size_t b : bonds_of[*worst]) bonds[b].active = false;
        group.erase(worst);
        changed = true;
      }
    }
    if (!changed) {
      out.converged = true;
      break;
    }
  }

  const Components c = active_components(n, bonds);
  out.label = c.label;
  out.size = c.size;
  const auto groups = c.members();
  for (std::size_t k = 0; k < c.count(); ++k) {
    if (groups[k].size() >= 2) {
      const UniaxialOrder u = local_order(groups[k], e);
      out.director.push_back(u.director);
      out.order.push_back(u.order);
    } else {
      out.director.push_back(e[groups[k].front()]);
      out.order.push_back(1.0);
    }
  }
  return out;
}

// ---- the stage ------------------------------------------------------------------------------------

NematicClusterAnalysis::NematicClusterAnalysis(NematicClusterSettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), replicas_(replicas), config_file_(std::move(config_file)) {
  check_nematic_cluster_settings(s_, config_file_);
}

void NematicClusterAnalysis::add_configuration(Sample& smp, const NematicClustering& c) const {
  smp.configurations += 1;
  smp.total += static_cast<double>(c.size.size());
  std::size_t largest = 0, particles = 0;
  for (std::size_t k = 0; k < c.size.size(); ++k) {
    const std::size_t l = c.size[k];
    largest = std::max(largest, l);
    particles += l;
    if (smp.counts.size() < l) smp.counts.resize(l, 0.0);
    smp.counts[l - 1] += 1;
    if (l < 2) continue;
    // |cos θ| between the director and each box axis; |n_a| = 1 falls in the last bin
    smp.directors += 1;
    for (int a = 0; a < 3; ++a) {
      const double x = std::abs(c.director[k][a]);
      const std::size_t bin = std::min(s_.cos_bins - 1, static_cast<std::size_t>(x * static_cast<double>(s_.cos_bins)));
      smp.cos_counts[static_cast<std::size_t>(a) * s_.cos_bins + bin] += 1;
    }
  }
  smp.largest_fraction += particles > 0 ? static_cast<double>(largest) / static_cast<double>(particles) : 0.0;
}

void NematicClusterAnalysis::accumulate(const Trajectory& t, int species_index) {
  const std::vector<std::size_t> members = t.members(species_index);
  if (members.empty()) throw InputError(t.path, "", "no particles of the selected species");
  std::vector<Sample> per_config;
  std::vector<Vec3> r(members.size()), e(members.size());
  for (std::size_t f = 0; f < t.frames; ++f) {
    for (std::size_t m = 0; m < members.size(); ++m) {
      r[m] = t.pos(f, members[m]);
      e[m] = t.axis(f, members[m], s_.axis);
    }
    const NematicClustering c = nematic_clusters(r, e, Box(t.box_edges(f)), s_);
    Sample smp;
    smp.cos_counts.assign(3 * s_.cos_bins, 0.0);
    add_configuration(smp, c);
    per_config.push_back(std::move(smp));

    NematicConfiguration nc;
    nc.replica = replicas_seen_;
    nc.frame = t.file_frame(f);
    nc.time = t.time[f];
    nc.clusters = c.size.size();
    nc.particles = members.size();
    nc.passes = c.passes;
    nc.converged = c.converged;
    for (std::size_t k = 0; k < c.size.size(); ++k) {
      nc.largest = std::max(nc.largest, c.size[k]);
      if (c.size[k] < 2) continue;
      nc.multi_size.push_back(c.size[k]);
      nc.multi_director.push_back(c.director[k]);
      nc.multi_order.push_back(c.order[k]);
    }
    configs_.push_back(std::move(nc));
  }
  // one sample per replica; with a single replica, ≤ 10 contiguous blocks of configurations (spec 50 §0)
  const std::size_t blocks = replicas_ > 1 ? 1 : std::min<std::size_t>(10, per_config.size());
  for (std::size_t b = 0; b < blocks; ++b) {
    Sample merged;
    merged.cos_counts.assign(3 * s_.cos_bins, 0.0);
    for (std::size_t k = b * per_config.size() / blocks; k < (b + 1) * per_config.size() / blocks; ++k) {
      const Sample& p = per_config[k];
      merged.configurations += p.configurations;
      merged.total += p.total;
      merged.largest_fraction += p.largest_fraction;
      merged.directors += p.directors;
      if (merged.counts.size() < p.counts.size()) merged.counts.resize(p.counts.size(), 0.0);
      for (std::size_t l = 0; l < p.counts.size(); ++l) merged.counts[l] += p.counts[l];
      for (std::size_t q = 0; q < p.cos_counts.size(); ++q) merged.cos_counts[q] += p.cos_counts[q];
    }
    samples_.push_back(std::move(merged));
  }
  ++replicas_seen_;
}

NematicClusterResult NematicClusterAnalysis::compute() const {
  NematicClusterResult r;
  r.per_configuration = configs_;
  r.configurations = configs_.size();
  r.samples = samples_.size();
  for (const auto& c : configs_)
    if (!c.converged) ++r.unconverged;
  std::size_t largest = 1;
  for (const auto& s : samples_) largest = std::max(largest, s.counts.size());
  for (std::size_t l = 1; l <= largest; ++l) r.size.push_back(static_cast<double>(l));

  CurveSamples counts;
  std::array<CurveSamples, 3> cos;
  std::vector<double> total, fraction;
  const double width = 1.0 / static_cast<double>(s_.cos_bins);
  for (const auto& s : samples_) {
    std::vector<double> c(largest, 0.0);
    for (std::size_t l = 0; l < s.counts.size(); ++l) c[l] = s.counts[l] / s.configurations;
    counts.add(std::move(c));
    total.push_back(s.total / s.configurations);
    fraction.push_back(s.largest_fraction / s.configurations);
    r.directors += static_cast<std::size_t>(s.directors);
    for (std::size_t a = 0; a < 3; ++a) {
      std::vector<double> d(s_.cos_bins, kNaN);
      if (s.directors > 0)
        for (std::size_t b = 0; b < s_.cos_bins; ++b) d[b] = s.cos_counts[a * s_.cos_bins + b] / (s.directors * width);
      cos[a].add(std::move(d));
    }
  }
  r.mean_count = counts.mean();
  r.mean_count_error = counts.standard_error();
  r.total = mean_and_error(total);
  r.largest_fraction = mean_and_error(fraction);
  for (std::size_t b = 0; b < s_.cos_bins; ++b) r.cos_center.push_back((static_cast<double>(b) + 0.5) * width);
  for (std::size_t a = 0; a < 3; ++a) {
    r.cos_density[a] = cos[a].mean();
    r.cos_density_error[a] = cos[a].standard_error();
    if (r.cos_density[a].empty()) r.cos_density[a].assign(s_.cos_bins, kNaN);
    if (r.cos_density_error[a].empty()) r.cos_density_error[a].assign(s_.cos_bins, kNaN);
  }
  return r;
}

}  // namespace anisodyn::analysis
