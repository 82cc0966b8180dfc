#include "anisodyn/analysis/flow_profiles.hpp"

#include <cmath>
#include <functional>
#include <numbers>

#include "anisodyn/core/error.hpp"
#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

namespace {

double bin_width(const io::H5mdReader& r, const std::string& name) {
  const auto text = r.observable_attribute(name, "bin_width");
  if (!text) throw InputError(r.path(), "/observables/" + name + "@bin_width", "expected the attribute bin_width");
  return std::stod(*text);
}

/// Adds rows [begin, end) of an observable to `sum` (sized to its width).
void add_rows(const io::H5mdReader::Series& s, std::size_t begin, std::size_t end, std::vector<double>& sum) {
  sum.resize(s.width, 0.0);
  for (std::size_t row = begin; row < end; ++row)
    for (std::size_t k = 0; k < s.width; ++k) sum[k] += s.value[row * s.width + k];
}

/// A sample's sums as one vector, rows first, then the five profiles: the form of the shared
/// jackknife (replica_statistics.hpp). Every estimate below is a ratio of sums, so the mean of the
/// samples gives the same estimates as their total.
std::vector<double> flatten(const ProfileSums& x) {
  std::vector<double> v{x.rows};
  for (const auto* part : {&x.z_count, &x.z_vx, &x.r_count, &x.r_mid_count, &x.r_mid_vx}) v.insert(v.end(), part->begin(), part->end());
  return v;
}

/// The inverse of flatten, for sums of the same bins as `shape`.
ProfileSums unflatten(const std::vector<double>& v, const ProfileSums& shape) {
  ProfileSums x = shape;
  x.rows = v[0];
  std::size_t at = 1;
  for (auto* part : {&x.z_count, &x.z_vx, &x.r_count, &x.r_mid_count, &x.r_mid_vx})
    for (double& value : *part) value = v[at++];
  return x;
}

double ratio(double a, double b) { return b > 0.0 ? a / b : NAN; }

/// Everything the result reports, as one vector, from pooled sums (so that the jackknife treats all alike).
struct Estimates {
  std::vector<double> density_z, vx_z, density_r, vx_r;
  double slip = NAN, gradient = NAN, v_top = NAN, shear_rate = NAN, v_mean = NAN, amplitude = NAN, viscosity = NAN;
  std::size_t fit_bins = 0;
};

/// A and η of the periodic Poiseuille profile (flow_profiles.hpp) from the slab velocities.
void fit_poiseuille(const FlowGeometry& g, const ProfileSums& t, const PoiseuilleSettings& p, Estimates& e) {
  const std::size_t bins = t.z_count.size();
  const double h = 0.5 * static_cast<double>(bins) * g.z_bin;
  std::vector<double> x(bins);  // ±u (h − u); empty slabs have v_x NaN, which fit_line skips
  double count = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    count += t.z_count[k];
    const double z = (static_cast<double>(k) + 0.5) * g.z_bin, u = z < h ? z : z - h;
    x[k] = (z < h ? 1.0 : -1.0) * u * (h - u);
  }
  const LinearFit fit = fit_line(x, e.vx_z);
  if (fit.points < 3) return;
  e.amplitude = fit.slope;
  const double density = count / t.rows / (g.area * 2.0 * h);
  e.viscosity = density * p.force / (2.0 * e.amplitude);
}

Estimates estimate(const FlowGeometry& g, const ProfileSums& t, const std::optional<SlipFitSettings>& slip,
                   const std::optional<PoiseuilleSettings>& poiseuille) {
  Estimates e;
  const double rows = t.rows;
  for (std::size_t k = 0; k < t.z_count.size(); ++k) {
    e.density_z.push_back(t.z_count[k] / rows / (g.area * g.z_bin));
    e.vx_z.push_back(ratio(t.z_vx[k], t.z_count[k]));
  }
  for (std::size_t k = 0; k < t.r_count.size(); ++k) {
    const double a = static_cast<double>(k) * g.r_bin, b = a + g.r_bin;
    e.density_r.push_back(t.r_count[k] / rows / (4.0 * std::numbers::pi / 3.0 * (b * b * b - a * a * a)));
    e.vx_r.push_back(ratio(t.r_mid_vx[k], t.r_mid_count[k]));
  }
  double all_v = 0.0, all_n = 0.0;
  for (std::size_t k = 0; k < t.z_count.size(); ++k) all_v += t.z_vx[k], all_n += t.z_count[k];
  e.v_mean = ratio(all_v, all_n);
  if (poiseuille && !t.z_count.empty()) fit_poiseuille(g, t, *poiseuille, e);
  if (!slip || t.z_count.empty()) return e;
  double sz = 0, sv = 0, szz = 0, szv = 0, n = 0, top_v = 0, top_n = 0;
  for (std::size_t k = 0; k < t.z_count.size(); ++k) {
    const double z = (static_cast<double>(k) + 0.5) * g.z_bin;
    if (z >= slip->fit_from && z <= slip->fit_to && std::isfinite(e.vx_z[k])) {
      sz += z, sv += e.vx_z[k], szz += z * z, szv += z * e.vx_z[k], n += 1;
    }
    if (z >= slip->top_from && z < slip->top_to) top_v += t.z_vx[k], top_n += t.z_count[k];
  }
  e.fit_bins = static_cast<std::size_t>(n);
  if (n >= 2) {
    e.gradient = (n * szv - sz * sv) / (n * szz - sz * sz);
    const double intercept = (sv - e.gradient * sz) / n;
    e.slip = intercept / e.gradient;
  }
  e.v_top = ratio(top_v, top_n);
  e.shear_rate = e.v_top / slip->height;
  return e;
}

}  // namespace

RunProfiles read_profiles(const std::string& path, std::size_t blocks, const std::function<bool(double)>& keep) {
  const io::H5mdReader r(path);
  RunProfiles out;
  const bool slabs = r.has_observable("profile_z_count"), shells = r.has_observable("profile_r_count");
  if (!slabs && !shells)
    throw InputError(path, "/observables/profile_z_count", "expected the profiles of anisodyn-dpd's \"profiles\" key (profile_z_* or profile_r_*)");
  std::vector<io::H5mdReader::Series> series;
  const std::vector<std::string> names = {"profile_z_count", "profile_z_vx_sum", "profile_r_count", "profile_r_midplane_count",
                                          "profile_r_midplane_vx_sum"};
  for (const std::string& name : names) series.push_back(r.has_observable(name) ? r.read_observable(name) : io::H5mdReader::Series{});
  if (slabs) {
    out.geometry.z_bin = bin_width(r, "profile_z_count");
    const auto edges = r.box_edges_frames();
    out.geometry.area = edges.at(0) * edges.at(1);
  }
  if (shells) out.geometry.r_bin = bin_width(r, "profile_r_count");
  // The kept rows, split into contiguous blocks.
  const io::H5mdReader::Series& first = slabs ? series[0] : series[2];
  std::vector<std::size_t> kept;
  for (std::size_t row = 0; row < first.rows(); ++row)
    if (keep(first.time[row])) kept.push_back(row);
  if (kept.size() < blocks)
    throw InputError(path, "/observables/" + std::string(slabs ? names[0] : names[2]),
                     "expected at least " + std::to_string(blocks) + " profile rows in the window, got " + std::to_string(kept.size()));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t begin = kept[kept.size() * b / blocks], end = kept[kept.size() * (b + 1) / blocks - 1] + 1;
    ProfileSums s;
    s.rows = static_cast<double>(end - begin);
    std::vector<double>* target[] = {&s.z_count, &s.z_vx, &s.r_count, &s.r_mid_count, &s.r_mid_vx};
    for (std::size_t k = 0; k < names.size(); ++k)
      if (series[k].rows()) add_rows(series[k], begin, end, *target[k]);
    out.samples.push_back(std::move(s));
  }
  return out;
}

FlowResult compute_flow(const FlowGeometry& g, const std::vector<ProfileSums>& samples, const std::optional<SlipFitSettings>& slip,
                        const std::optional<PoiseuilleSettings>& poiseuille) {
  FlowResult r;
  r.samples = samples.size();
  CurveSamples sums;
  for (const ProfileSums& x : samples) {
    sums.add(flatten(x));
    r.rows += static_cast<std::size_t>(x.rows);
  }
  const ProfileSums& shape = samples.front();
  const std::size_t nz = shape.z_count.size(), nr = shape.r_count.size();
  // Every reported estimate as one vector: density_z, v_x(z), density_r, v_x(r), then the scalars.
  const auto estimates = [&](const std::vector<double>& mean) {
    const Estimates e = estimate(g, unflatten(mean, shape), slip, poiseuille);
    std::vector<double> out;
    for (const auto* part : {&e.density_z, &e.vx_z, &e.density_r, &e.vx_r}) out.insert(out.end(), part->begin(), part->end());
    out.insert(out.end(), {e.v_mean, e.slip, e.gradient, e.v_top, e.shear_rate, e.amplitude, e.viscosity});
    return out;
  };
  const CurveEstimate est = jackknife_curve(sums, estimates);
  auto at = [&](std::size_t k) { return ValueError{est.value[k], est.error[k]}; };
  for (std::size_t k = 0; k < nz; ++k) {
    r.z.push_back((static_cast<double>(k) + 0.5) * g.z_bin);
    r.density_z.push_back(est.value[k]);
    r.density_z_se.push_back(est.error[k]);
    r.vx_z.push_back(est.value[nz + k]);
    r.vx_z_se.push_back(est.error[nz + k]);
  }
  for (std::size_t k = 0; k < nr; ++k) {
    r.r.push_back((static_cast<double>(k) + 0.5) * g.r_bin);
    r.density_r.push_back(est.value[2 * nz + k]);
    r.density_r_se.push_back(est.error[2 * nz + k]);
    r.vx_r.push_back(est.value[2 * nz + nr + k]);
    r.vx_r_se.push_back(est.error[2 * nz + nr + k]);
  }
  const std::size_t scalars = 2 * nz + 2 * nr;
  if (nz > 0) r.v_mean = at(scalars);
  if (slip && nz > 0) {
    r.slip_length = at(scalars + 1);
    r.gradient = at(scalars + 2);
    r.v_top = at(scalars + 3);
    r.shear_rate = at(scalars + 4);
    r.fit_bins = estimate(g, unflatten(mean_curve(sums.samples()), shape), slip, poiseuille).fit_bins;
  }
  if (poiseuille && nz > 0) {
    r.poiseuille_amplitude = at(scalars + 5);
    r.viscosity = at(scalars + 6);
  }
  return r;
}

}  // namespace anisodyn::analysis
