#include "anisodyn/analysis/pair_structure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "anisodyn/analysis/frame_window.hpp"
#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/core/box.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/system/order.hpp"

namespace anisodyn::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Histogram geometry of one frame: bins of width dr up to r_cut; the cylinder (radius R) and
/// slab (half height h) about the unit vector e; directional = false skips g_∥ and g_⊥.
struct PairGeometry {
  Vec3 L, e;
  double dr, r_cut, R, h;
  bool directional;
};

/// Adds the pair counts Σ_i Σ_j (j ≠ i) of one frame to cg, cpar, cperp: the pairs of a (b null:
/// like pairs, met once and counted twice) or of a × b, found by the cell lists of pair_search.hpp
/// at the minimum image.
void count_pairs(const std::vector<Vec3>& a, const std::vector<Vec3>* b, const PairGeometry& g, std::vector<double>& cg,
                 std::vector<double>& cpar, std::vector<double>& cperp) {
  const std::size_t nb = cg.size();
  const double weight = b ? 1.0 : 2.0;
  const double r_cut2 = g.r_cut * g.r_cut;
  const double reach = g.directional ? std::max(g.R, g.h) : 0.0;
  const double any2 = r_cut2 + reach * reach;  // beyond this no histogram can receive the pair
  const double inv_dr = 1.0 / g.dr;
  auto count = [&](std::size_t, std::size_t, const Vec3& d, double r2) {
    if (r2 >= any2) return;
    if (r2 < r_cut2) cg[std::min(nb - 1, static_cast<std::size_t>(std::sqrt(r2) * inv_dr))] += weight;
    if (!g.directional) return;
    const double x = std::abs(d.x() * g.e.x() + d.y() * g.e.y() + d.z() * g.e.z());
    const double perp = std::sqrt(std::max(r2 - x * x, 0.0));
    if (perp < g.R && x < g.r_cut) cpar[std::min(nb - 1, static_cast<std::size_t>(x * inv_dr))] += weight;
    if (x < g.h && perp < g.r_cut) cperp[std::min(nb - 1, static_cast<std::size_t>(perp * inv_dr))] += weight;
  };
  // The search reaches a hair beyond √any2; the test above decides, as in the O(N²) loop before it.
  const PairGrid grid(g.L, std::sqrt(any2) * (1 + 1e-9), a.size() + (b ? b->size() : 0));
  if (b) grid.for_each_pair(grid.sort(a), grid.sort(*b), count);
  else grid.for_each_pair(grid.sort(a), count);
}
}  // namespace

PairStructureSettings parse_structure_settings(tool::ConfigNode& cfg) {
  PairStructureSettings s;
  if (cfg.has("pairs")) {
    const nlohmann::json& p = cfg.value("pairs");
    if (!p.is_array()) cfg.fail("pairs", "expected a list of species pairs, e.g. [[\"A\", \"B\"]]");
    for (const auto& e : p) {
      if (!e.is_array() || e.size() != 2 || !e[0].is_string() || !e[1].is_string())
        cfg.fail("pairs", "expected a list of species pairs, e.g. [[\"A\", \"B\"]]");
      s.pairs.emplace_back(e[0].get<std::string>(), e[1].get<std::string>());
    }
  }
  s.dr = cfg.positive("dr", s.dr);
  if (cfg.has("r_max")) s.r_max = cfg.positive("r_max");
  const std::string ref = cfg.choice("reference", {"field", "director", "none"}, "field");
  s.reference = ref == "director" ? PairReference::Director : ref == "none" ? PairReference::None : PairReference::Field;
  cfg.reject_unless(ref == "field", "direction", "unless \"reference\" is \"field\" (it is the field's direction)");
  for (const char* key : {"axis", "director_species"})
    cfg.reject_unless(ref == "director", key, "unless \"reference\" is \"director\" (it chooses the director)");
  for (const char* key : {"cylinder_radius", "slab_half_height"})
    cfg.reject_unless(ref != "none", key, "with \"reference\" \"none\" (it shapes g_par and g_perp)");
  const Vec3 d = cfg.vec3("direction", Vec3::UnitZ());
  if (!(d.norm() > 0)) cfg.fail("direction", "expected a non-zero direction vector");
  s.direction = d.normalized();
  s.axis = parse_body_axis(cfg, "axis", "auto", true);
  s.director_species = cfg.string("director_species", "");
  s.cylinder_radius = cfg.positive("cylinder_radius", s.cylinder_radius);
  s.slab_half_height = cfg.positive("slab_half_height", s.slab_half_height);
  s.slab_bins = static_cast<std::size_t>(cfg.positive_integer("slab_bins", 50));
  refuse_frame_key(cfg, "frames");
  return s;
}

PairStructureAnalysis::PairStructureAnalysis(PairStructureSettings settings, std::size_t replicas, std::string config_file)
    : s_(std::move(settings)), replicas_(replicas), config_file_(std::move(config_file)) {}

void PairStructureAnalysis::resolve_species(const Trajectory& t) {
  if (s_.pairs.empty())  // each species present with itself
    for (std::size_t sp = 0; sp < t.species_table.size(); ++sp)
      if (!t.members(static_cast<int>(sp)).empty()) s_.pairs.emplace_back(t.species_table[sp].name, t.species_table[sp].name);
  for (std::size_t k = 0; k < s_.pairs.size(); ++k) {
    const std::string where = "pairs[" + std::to_string(k) + "]";
    const int a = t.species_index(s_.pairs[k].first, config_file_, where);
    const int b = t.species_index(s_.pairs[k].second, config_file_, where);
    pair_index_.emplace_back(a, b);
    pair_names_a_.push_back(s_.pairs[k].first);
    pair_names_b_.push_back(s_.pairs[k].second);
    count_a_.push_back(t.members(a).size());
    count_b_.push_back(t.members(b).size());
    if (count_a_.back() == 0 || count_b_.back() == 0)
      throw InputError(config_file_, where, "species without particles in " + t.path);
    for (int s : {a, b})
      if (std::find(profile_species_.begin(), profile_species_.end(), s) == profile_species_.end()) {
        profile_species_.push_back(s);
        profile_names_.push_back(t.species_table[static_cast<std::size_t>(s)].name);
      }
  }
  rho_b_sum_.assign(pair_index_.size(), 0.0);
  // r_max: half the smallest edge the box ever has, so every shell fits in the minimum-image cell
  double half = INFINITY;
  for (std::size_t f = 0; f < t.frames; ++f) half = std::min(half, 0.5 * t.box_edges(f).minCoeff());
  if (s_.r_max == 0.0) s_.r_max = half;
  if (s_.r_max > half * (1 + 1e-12))
    throw InputError(config_file_, "r_max", "r_max = " + std::to_string(s_.r_max) + " exceeds half the smallest box edge (" +
                                                std::to_string(half) + "); pairs beyond it are not unique under the minimum image");
  bins_ = static_cast<std::size_t>(std::floor(s_.r_max / s_.dr * (1 + 1e-12)));
  if (bins_ == 0) throw InputError(config_file_, "dr", "expected dr ≤ r_max");
  for (std::size_t b = 0; b < bins_; ++b) meta_.r.push_back((static_cast<double>(b) + 0.5) * s_.dr);
}

std::vector<Vec3> PairStructureAnalysis::frame_reference(const Trajectory& t, const std::vector<std::size_t>& frames) {
  std::vector<Vec3> e(frames.size(), s_.direction);
  if (s_.reference != PairReference::Director) return e;
  // Director species: the named one, else the first anisotropic species of the pairs, else of the file.
  int ds = -1;
  if (!s_.director_species.empty()) {
    ds = t.species_index(s_.director_species, config_file_, "director_species");
    if (!t.species_table[static_cast<std::size_t>(ds)].shape.is_anisotropic())
      throw InputError(config_file_, "director_species", "species '" + s_.director_species + "' is a sphere: it has no director");
  } else {
    for (const auto& [a, b] : pair_index_)
      for (int s : {a, b})
        if (ds < 0 && t.species_table[static_cast<std::size_t>(s)].shape.is_anisotropic()) ds = s;
    for (std::size_t s = 0; s < t.species_table.size() && ds < 0; ++s)
      if (t.species_table[s].shape.is_anisotropic()) ds = static_cast<int>(s);
    if (ds < 0) throw InputError(config_file_, "reference", "a director was requested but " + t.path + " has no anisotropic species");
  }
  const auto members = t.members(ds);
  std::vector<std::array<Mat3, 3>> q;
  Vec3 mean_u = Vec3::Zero();
  for (std::size_t f : frames) {
    q.push_back(axis_q_tensors(frame_rotations(t, f, members)));
    for (std::size_t k = 0; k < 3; ++k) mean_u[static_cast<int>(k)] += uniaxial_order(q.back()[k]).order / static_cast<double>(frames.size());
  }
  int axis = s_.axis;
  if (axis < 0) mean_u.maxCoeff(&axis);
  const double order = mean_u[axis];
  // The director is taken per frame (it may drift over a long run); the order check uses the
  // frame-mean U of that axis.
  if (!(order > s_.director_threshold))
    throw InputError(config_file_, "reference",
                     "a director was requested but " + t.path + " has no orientational order: the mean largest eigenvalue of Q^" +
                         std::string(axis_letter(axis)) + " is U = " + std::to_string(order) + " ≤ " + std::to_string(s_.director_threshold) +
                         " (isotropic); use \"reference\": \"field\" with a direction, or \"none\"");
  for (std::size_t k = 0; k < frames.size(); ++k) e[k] = uniaxial_order(q[k][static_cast<std::size_t>(axis)]).director;
  meta_.director_axis.push_back(axis);
  meta_.director_order.push_back(order);
  return e;
}

void PairStructureAnalysis::accumulate(const Trajectory& t) {
  if (t.position.empty()) throw RuntimeFailure("PairStructureAnalysis needs positions");
  if (pair_index_.empty()) resolve_species(t);
  std::vector<std::size_t> frames(t.frames);  // every loaded frame: the window chose them
  std::iota(frames.begin(), frames.end(), std::size_t{0});
  const std::vector<Vec3> ref = frame_reference(t, frames);
  frames_per_replica_ = frames.size();
  const std::size_t nb = bins_, ns = s_.slab_bins, np = pair_index_.size();
  const std::size_t width = np * 3 * nb + profile_species_.size() * 3 * ns;
  const std::size_t blocks = replicas_ == 1 ? std::max<std::size_t>(1, std::min(s_.single_replica_blocks, frames.size())) : 1;
  std::vector<std::vector<double>> sums(blocks, std::vector<double>(width, 0.0));
  std::vector<double> block_frames(blocks, 0.0);
  // the histogram ends at the last whole bin, r_cut = bins · Δr ≤ r_max
  const double dr = s_.dr, R = s_.cylinder_radius, h = s_.slab_half_height, r_max = static_cast<double>(nb) * dr;
  std::vector<std::vector<std::size_t>> members_a(np), members_b(np);
  for (std::size_t p = 0; p < np; ++p) {
    members_a[p] = t.members(pair_index_[p].first);
    members_b[p] = t.members(pair_index_[p].second);
  }
  std::vector<double> cg(nb), cpar(nb), cperp(nb);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::size_t f = frames[k], blk = k * blocks / frames.size();
    const Vec3 L = t.box_edges(f);
    const double V = L.prod(), half_cell = 0.5 * L.minCoeff();
    if (r_max > half_cell * (1 + 1e-9))
      throw InputError(t.path, "/particles/all/box", "frame " + std::to_string(f) + " has a box smaller than twice r_max = " +
                                                         std::to_string(r_max) + " (set r_max for the smallest box of all replicas)");
    const Vec3 e = ref[k];
    std::vector<double>& out = sums[blk];
    for (std::size_t p = 0; p < np; ++p) {
      std::fill(cg.begin(), cg.end(), 0.0);
      std::fill(cpar.begin(), cpar.end(), 0.0);
      std::fill(cperp.begin(), cperp.end(), 0.0);
      const bool same = pair_index_[p].first == pair_index_[p].second;
      const auto& A = members_a[p];
      const auto& B = members_b[p];
      const PairGeometry geometry{L, e, dr, r_max, R, h, s_.reference != PairReference::None};
      const std::vector<Vec3> ra = frame_positions(t, f, A);
      const std::vector<Vec3> rb = same ? std::vector<Vec3>{} : frame_positions(t, f, B);
      count_pairs(ra, same ? nullptr : &rb, geometry, cg, cpar, cperp);
      const double na = static_cast<double>(A.size()), rho = static_cast<double>(B.size()) / V;
      rho_b_sum_[p] += rho;
      double* g = &out[p * 3 * nb];
      for (std::size_t b = 0; b < nb; ++b) {
        const double r0 = static_cast<double>(b) * dr, r1 = r0 + dr;
        const double v = 4.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) / 3.0;
        const double v_par = 2.0 * M_PI * R * R * dr;
        const double v_perp = M_PI * (r1 * r1 - r0 * r0) * 2.0 * h;
        g[b] += cg[b] / (na * rho * v);
        // a cylinder or slab that leaves the minimum-image cell would be counted incompletely
        const bool par_ok = std::hypot(r1, R) <= half_cell, perp_ok = std::hypot(r1, h) <= half_cell;
        g[nb + b] += par_ok && s_.reference != PairReference::None ? cpar[b] / (na * rho * v_par) : kNaN;
        g[2 * nb + b] += perp_ok && s_.reference != PairReference::None ? cperp[b] / (na * rho * v_perp) : kNaN;
      }
    }
    for (std::size_t sp = 0; sp < profile_species_.size(); ++sp) {
      const auto members = t.members(profile_species_[sp]);
      double* rho = &out[np * 3 * nb + sp * 3 * ns];
      // ρ_r = count / (A Δs) / (N/V) = count · n_bins / N with A Δs = V / n_bins
      const double scale = static_cast<double>(ns) / static_cast<double>(members.size());
      for (std::size_t i : members) {
        const Vec3 r = t.pos(f, i);
        for (int a = 0; a < 3; ++a) {
          double u = r[a] / L[a];
          u -= std::floor(u);
          const std::size_t bin = std::min(ns - 1, static_cast<std::size_t>(u * static_cast<double>(ns)));
          rho[static_cast<std::size_t>(a) * ns + bin] += scale;
        }
      }
    }
    for (int a = 0; a < 3; ++a) edge_sum_[static_cast<std::size_t>(a)] += L[a];
    ++frame_count_;
    block_frames[blk] += 1.0;
  }
  for (std::size_t b = 0; b < blocks; ++b) {
    for (double& v : sums[b]) v /= block_frames[b];
    samples_.push_back(std::move(sums[b]));
  }
  meta_.blocks = blocks > 1;
}

PairStructureResult PairStructureAnalysis::compute() const {
  PairStructureResult r = meta_;
  CurveSamples samples;
  for (const auto& s : samples_) samples.add(s);
  const auto mean = samples.mean(), se = samples.standard_error();
  const std::size_t nb = bins_, ns = s_.slab_bins, np = pair_index_.size();
  auto slice = [](const std::vector<double>& v, std::size_t from, std::size_t n) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(from), v.begin() + static_cast<std::ptrdiff_t>(from + n));
  };
  for (std::size_t p = 0; p < np; ++p) {
    PairCurves c;
    c.a = pair_names_a_[p];
    c.b = pair_names_b_[p];
    c.count_a = count_a_[p];
    c.count_b = count_b_[p];
    c.g = slice(mean, p * 3 * nb, nb);
    c.g_se = slice(se, p * 3 * nb, nb);
    c.g_par = slice(mean, p * 3 * nb + nb, nb);
    c.g_par_se = slice(se, p * 3 * nb + nb, nb);
    c.g_perp = slice(mean, p * 3 * nb + 2 * nb, nb);
    c.g_perp_se = slice(se, p * 3 * nb + 2 * nb, nb);
    // running coordination number n_AB(r) = ρ_B Σ_{bins ≤ r} v g (ρ_B averaged over the frames)
    const double rho = frame_count_ ? rho_b_sum_[p] / static_cast<double>(frame_count_) : kNaN;
    double n = 0;
    for (std::size_t b = 0; b < nb; ++b) {
      const double r0 = static_cast<double>(b) * s_.dr, r1 = r0 + s_.dr;
      n += rho * 4.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) / 3.0 * c.g[b];
      c.coordination.push_back(n);
    }
    r.pairs.push_back(std::move(c));
  }
  for (std::size_t sp = 0; sp < profile_species_.size(); ++sp) {
    SlabProfile prof;
    prof.species = profile_names_[sp];
    for (std::size_t a = 0; a < 3; ++a) {
      const double L = frame_count_ ? edge_sum_[a] / static_cast<double>(frame_count_) : kNaN;
      for (std::size_t b = 0; b < ns; ++b) prof.s[a].push_back((static_cast<double>(b) + 0.5) / static_cast<double>(ns) * L);
      prof.rho[a] = slice(mean, np * 3 * nb + sp * 3 * ns + a * ns, ns);
      prof.rho_se[a] = slice(se, np * 3 * nb + sp * 3 * ns + a * ns, ns);
    }
    r.profiles.push_back(std::move(prof));
  }
  r.samples = samples.count();
  r.frames_per_replica = frames_per_replica_;
  switch (s_.reference) {
    case PairReference::None: r.reference = "none"; break;
    case PairReference::Field:
      r.reference = "field direction [" + std::to_string(s_.direction.x()) + ", " + std::to_string(s_.direction.y()) + ", " +
                    std::to_string(s_.direction.z()) + "]";
      break;
    case PairReference::Director: r.reference = "per-frame nematic director of the Q tensor of the chosen axis"; break;
  }
  return r;
}

}  // namespace anisodyn::analysis
