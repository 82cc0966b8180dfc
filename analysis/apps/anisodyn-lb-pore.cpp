// anisodyn-lb-pore: the enhanced drag of a raspberry in anisodyn-lb's cylindrical pore against its
// radial position (spec 40 §9, study D5): pore-frame MSDs per β bin over the first `lags` lags
// (analysis/pore_frame.hpp), D_i^p from a weighted line through them, and S_i = D_0 / D_i^p with D_0
// the unbounded diffusion coefficient at the same bead friction (a parameter: spec 40 §8.1's
// extrapolated value, in the run's units). Errors per bin: the standard deviation of the squared
// displacements over √(sub-trajectories / lags), the number of independent ones (spec 40 §9).
#include <algorithm>
#include <array>
#include <cmath>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/pore_frame.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/lb_run_summary.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

tool::Description description() {
  return analysis_description(
      {tool::required("D0", "number", "the unbounded D_0 at the same xi_bead, in the run's units (sigma^2/t0): S_i = D0 / D_i^p"),
       tool::optional("bin_width", "number", 0.05, "width of the beta bins (spec 40 §9)"),
       tool::optional("lags", "integer", 25, "the lags of each sub-trajectory and of the fit (spec 40 §9: the lowest 25 recordings)")},
      "table pore_bins (per beta bin: count, D_x, D_y, D_z, S_x, S_y, S_z with errors, small_beta flag); scalars S_x/y/z_centreline (beta < 0.1)");
}

struct PoreFacts {
  double radius = 0.0, gap = 0.0;
  Vec3 axis = Vec3::Zero();
};

PoreFacts pore_facts(const std::string& path) {
  const io::H5mdReader reader(path);
  const LbRunSummary run = read_lb_run_summary(reader, path, "pore");
  const auto semi = run.body.at("semi_axes").get<std::vector<double>>();
  PoreFacts f;
  f.radius = run.summary.at("pore").at("radius").get<double>();
  f.gap = f.radius - *std::max_element(semi.begin(), semi.end());
  const Vec3 edges = reader.read_frame(0).box.edges();
  f.axis = Vec3(0.5 * edges.x(), 0.5 * edges.y(), 0.0);
  return f;
}

/// D of one component from the MSD per lag: a line weighted by 1/SE² through lags 1 … K, slope / 2.
Estimate fit_diffusion(const std::vector<double>& lag, const std::vector<double>& msd, const std::vector<double>& se) {
  std::vector<double> w;
  for (double e : se) w.push_back(e > 0 ? 1.0 / (e * e) : 0.0);
  const LinearFit fit = fit_line(lag, msd, w);
  return {fit.slope / 2.0, fit.slope_error / 2.0};
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb-pore", "Enhanced drag of a raspberry in a pore against beta (spec 40 §9)", "See docs/lb.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const double d0 = run.cfg.positive("D0");
    PoreFrameBins bins;
    bins.bin_width = run.cfg.positive("bin_width", bins.bin_width);
    bins.lags = static_cast<std::size_t>(run.cfg.positive_integer("lags", static_cast<std::int64_t>(bins.lags)));
    run.cfg.finish();
    const PoreFacts facts = pore_facts(run.inputs.front());
    PoreFrameBins centreline = bins;  // β < 0.1 as one bin
    centreline.bin_width = 0.1;
    double spacing = 0.0;
    TrajectoryNeeds needs;
    needs.positions = true;
    needs.window = run.window;
    needs.min_frames = bins.lags + 1;
    run.each_replica(needs, [&](const Trajectory& tr, std::size_t) {
      if (tr.particles != 1) throw InputError(tr.path, "/particles/all", "one raspberry per run");
      const PoreFacts f = pore_facts(tr.path);
      if (std::abs(f.radius - facts.radius) > 1e-12 || std::abs(f.gap - facts.gap) > 1e-12 || (f.axis - facts.axis).norm() > 1e-12)
        throw InputError(tr.path, "/parameters", "the same pore and raspberry as " + run.inputs.front());
      const double dt = tr.time[1] - tr.time[0];
      for (std::size_t n = 1; n < tr.frames; ++n)
        if (std::abs(tr.time[n] - tr.time[n - 1] - dt) > 1e-6 * dt) throw InputError(tr.path, "/particles/all/position/time", "frames at a uniform spacing");
      if (spacing == 0.0) spacing = dt;
      if (std::abs(dt - spacing) > 1e-9 * spacing) throw InputError(tr.path, "/particles/all/position/time", "the frame spacing of the other runs");
      std::vector<Vec3> centre;
      for (std::size_t n = 0; n < tr.frames; ++n) centre.push_back(tr.pos(n, 0));
      accumulate_pore_bins(centre, facts.axis, facts.gap, bins);
      accumulate_pore_bins(centre, facts.axis, facts.gap, centreline);
    });
    std::vector<double> lag;
    for (std::size_t k = 1; k <= bins.lags; ++k) lag.push_back(static_cast<double>(k) * spacing);

    // Per bin and component: the MSD per lag with its error, the fitted D and S = D0/D.
    const auto estimate = [&](const PoreFrameBins& b, std::size_t bin, int i) -> Estimate {
      const double n = static_cast<double>(b.count[bin]);
      if (b.count[bin] < 2) return {};
      const double independent = std::max(1.0, n / static_cast<double>(b.lags));
      std::vector<double> msd, se;
      for (std::size_t k = 0; k < b.lags; ++k) {
        const double mean = b.sum[bin][k][i] / n;
        const double var = std::max(0.0, b.sum2[bin][k][i] / n - mean * mean);
        msd.push_back(mean);
        se.push_back(std::sqrt(var / independent));
      }
      return fit_diffusion(lag, msd, se);
    };
    std::vector<double> beta, count, small;
    std::array<std::vector<double>, 3> D, D_se, S, S_se;
    for (std::size_t bin = 0; bin < bins.count.size(); ++bin) {
      if (bins.count[bin] < 2) continue;
      beta.push_back((static_cast<double>(bin) + 0.5) * bins.bin_width);
      count.push_back(static_cast<double>(bins.count[bin]));
      small.push_back(beta.back() < 0.1 ? 1.0 : 0.0);
      for (int i = 0; i < 3; ++i) {
        const Estimate d = estimate(bins, bin, i);
        D[i].push_back(d.value), D_se[i].push_back(d.error);
        S[i].push_back(d0 / d.value), S_se[i].push_back(std::abs(d0 / d.value) * d.error / std::abs(d.value));
      }
    }
    if (beta.empty()) run.fail("lags", "expected runs longer than lags + 1 frames: no bin has two sub-trajectories");
    const char* axis[3] = {"x", "y", "z"};
    const char* meaning[3] = {"radial", "azimuthal", "axial"};
    Table& t = run.out.table("pore_bins", "spec 40 §9: per beta bin, the pore-frame D_i^p from the MSD over the first lags and S_i = D0 / D_i^p");
    t.add("beta", "1", "bin centre of beta = d / (R_pore - R)", beta);
    t.add("count", "1", "sub-trajectories starting in the bin", count);
    t.add("small_beta", "1", "1 where beta < 0.1: the radial and azimuthal directions are ill-defined there (spec 40 §9)", small);
    for (int i = 0; i < 3; ++i) {
      const std::string a = axis[i];
      t.add("D_" + a, "sigma^2/t0", std::string("pore-frame D along ") + meaning[i] + " x^p_" + a, D[i]);
      t.add("D_" + a + "_se", "sigma^2/t0", "its error", D_se[i]);
      t.add("S_" + a, "1", std::string("enhanced drag D0 / D_") + a + " (" + meaning[i] + ")", S[i]);
      t.add("S_" + a + "_se", "1", "its error", S_se[i]);
    }
    const nlohmann::json details = {{"D0", d0}, {"gap", facts.gap}, {"pore_radius", facts.radius}, {"lags", bins.lags}, {"bin_width", bins.bin_width},
                                    {"centreline_count", centreline.count.empty() ? 0 : centreline.count[0]}};
    for (int i = 0; i < 3; ++i) {
      const Estimate d = centreline.count.empty() ? Estimate{} : estimate(centreline, 0, i);
      run.out.scalar({std::string("S_") + axis[i] + "_centreline", d0 / d.value, std::abs(d0 / d.value) * d.error / std::abs(d.value), "1",
                      std::string("D0 / D_") + axis[i] + " of the sub-trajectories starting at beta < 0.1 (" + meaning[i] + "; x, y ill-defined there)", details});
    }
  });
}
