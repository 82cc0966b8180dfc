// anisodyn-flow: steady-flow profiles of anisodyn-dpd runs (spec 30 §6 and §8; studies C2, C3):
// density and v_x across the channel between walls, with the slip length of the Couette method,
// the viscosity of a periodic Poiseuille flow, and density and mid-plane v_x around a colloid held
// in a flow. The rows inside `window` (the steady state) are averaged; errors are jackknife over
// replicas (or blocks of a single replica).
#include <cstdio>

#include "anisodyn/analysis/flow_profiles.hpp"
#include "anisodyn/analysis/stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

std::optional<SlipFitSettings> parse_slip(StageRun& run) {
  auto node = run.cfg.optional_object("slip");
  if (!node) return std::nullopt;
  SlipFitSettings s;
  s.fit_from = node->non_negative("fit_from", s.fit_from);
  s.fit_to = node->positive("fit_to", s.fit_to);
  s.top_from = node->non_negative("top_from", s.top_from);
  s.top_to = node->positive("top_to", s.top_to);
  s.height = node->positive("height", s.height);
  if (!(s.fit_to > s.fit_from)) run.fail("slip.fit_to", "expected fit_to > fit_from");
  if (!(s.top_to > s.top_from)) run.fail("slip.top_to", "expected top_to > top_from");
  return s;
}

std::optional<PoiseuilleSettings> parse_poiseuille(StageRun& run) {
  auto node = run.cfg.optional_object("poiseuille");
  if (!node) return std::nullopt;
  PoiseuilleSettings p;
  p.force = node->positive("force");
  return p;
}

void write_tables(StageRun& run, const FlowResult& r) {
  if (!r.z.empty()) {
    Table& t = run.out.table("profile_z", "spec 30 §6: liquid density and mean v_x per slab along z, over the window's rows");
    t.add("z", "r_c", "slab centre", r.z);
    t.add("density", "r_c^-3", "mean number per slab / (area x slab width)", r.density_z);
    t.add("density_se", "r_c^-3", "jackknife standard error of density", r.density_z_se);
    t.add("v_x", "r_c/tau", "sum of v_x / number of liquid particles in the slab", r.vx_z);
    t.add("v_x_se", "r_c/tau", "jackknife standard error of v_x", r.vx_z_se);
  }
  if (!r.r.empty()) {
    Table& t = run.out.table("profile_r", "spec 30 §8: liquid density per shell around the colloid and v_x in its mid-plane slab");
    t.add("r", "r_c", "shell centre (distance from the colloid's centre)", r.r);
    t.add("density", "r_c^-3", "mean number per shell / shell volume", r.density_r);
    t.add("density_se", "r_c^-3", "jackknife standard error of density", r.density_r_se);
    t.add("v_x", "r_c/tau", "sum of v_x / number of liquid particles of the shell in the mid-plane slab |x - x_c| < half width", r.vx_r);
    t.add("v_x_se", "r_c/tau", "jackknife standard error of v_x", r.vx_r_se);
  }
}

void write_scalars(StageRun& run, const FlowResult& r, const SlipFitSettings& s) {
  const nlohmann::json details = {{"fit_from", s.fit_from}, {"fit_to", s.fit_to}, {"fit_bins", r.fit_bins}, {"top_from", s.top_from},
                                  {"top_to", s.top_to}, {"height", s.height}, {"samples", r.samples}, {"rows", r.rows},
                                  {"error", "jackknife over the samples (replicas, or blocks of one replica)"}};
  run.out.scalar({"slip_length", r.slip_length->value, r.slip_length->error, "r_c",
                  "spec 30 §6: b = a/G of the line v_x = G z + a through the slab velocities in [fit_from, fit_to] (b > 0: slip)", details});
  run.out.scalar({"shear_gradient", r.gradient->value, r.gradient->error, "1/tau", "G, the slope of that line", details});
  run.out.scalar({"v_top", r.v_top->value, r.v_top->error, "r_c/tau", "mean v_x of the liquid in [top_from, top_to)", details});
  run.out.scalar({"shear_rate_apparent", r.shear_rate->value, r.shear_rate->error, "1/tau", "spec 30 §6: v_top / height", details});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-flow: slip length b = %.4g ± %.2g, G = %.4g ± %.2g, shear rate %.4g ± %.2g\n", r.slip_length->value,
                 r.slip_length->error, r.gradient->value, r.gradient->error, r.shear_rate->value, r.shear_rate->error);
}

void write_poiseuille_scalars(StageRun& run, const FlowResult& r, const PoiseuilleSettings& p) {
  const nlohmann::json details = {{"force", p.force}, {"samples", r.samples}, {"rows", r.rows},
                                  {"error", "jackknife over the samples (replicas, or blocks of one replica)"}};
  run.out.scalar({"poiseuille_amplitude", r.poiseuille_amplitude->value, r.poiseuille_amplitude->error, "1/(r_c tau)",
                  "A of v_x = +-A u (h - u) + B, the least-squares fit of the slab velocities (h: half the box along z)", details});
  run.out.scalar({"viscosity_poiseuille", r.viscosity->value, r.viscosity->error, "kT tau/r_c^3",
                  "eta = rho f / (2 A), rho the mean density of the slabs", details});
  if (!run.opt.quiet) std::fprintf(stderr, "anisodyn-flow: Poiseuille viscosity %.4g ± %.2g\n", r.viscosity->value, r.viscosity->error);
}

tool::Description description() {
  return analysis_description(
      {tool::optional("poiseuille", "object", nullptr,
                      "{force}: the viscosity of a periodic Poiseuille flow (no walls; anisodyn-dpd drives +force along x on the lower "
                      "half of the box and -force on the upper) from a fit of the slab profile"),
       tool::optional("slip", "object", nullptr,
                      "{fit_from (1.5), fit_to (5), top_from (7), top_to (8), height (8)}: the Couette slip length of spec 30 §6 from the "
                      "slab profile (absent: profiles only)"),
       tool::optional("blocks", "integer", 10, "a single replica's rows in this many blocks for the errors (several replicas: one sample each)")},
      "tables profile_z (density, v_x per slab) and profile_r (density, mid-plane v_x per shell); scalar v_x_mean with slabs; with "
      "slip, scalars slip_length, shear_gradient, v_top, shear_rate_apparent; with poiseuille, scalars viscosity_poiseuille and "
      "poiseuille_amplitude");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-flow", "steady-flow profiles and the Couette slip length of anisodyn-dpd runs", "See docs/analysis.md.",
                            description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const std::optional<SlipFitSettings> slip = parse_slip(run);
    const std::optional<PoiseuilleSettings> poiseuille = parse_poiseuille(run);
    if (slip && poiseuille) run.fail("poiseuille", "expected either slip (a channel between walls) or poiseuille (a periodic box), not both");
    const auto blocks = static_cast<std::size_t>(run.cfg.positive_integer("blocks", 10));
    run.cfg.reject_unless(run.inputs.size() == 1, "blocks", "with several replicas (each replica is one sample)");
    if (blocks < 2 && run.inputs.size() == 1) run.fail("blocks", "expected at least 2 blocks for an error bar");
    run.cfg.finish();
    std::vector<ProfileSums> samples;
    FlowGeometry geometry;
    for (std::size_t k = 0; k < run.inputs.size(); ++k) {
      run.report_replica(k, run.inputs[k]);
      RunProfiles p = read_profiles(run.inputs[k], run.inputs.size() == 1 ? blocks : 1, [&](double t) { return run.window.contains(t); });
      if (k == 0) geometry = p.geometry;
      else if (p.geometry.z_bin != geometry.z_bin || p.geometry.r_bin != geometry.r_bin || p.geometry.area != geometry.area)
        run.fail("inputs", "expected replicas with the same profile bins and box: " + run.inputs[k] + " differs from " + run.inputs[0]);
      for (ProfileSums& s : p.samples) samples.push_back(std::move(s));
    }
    if (slip && geometry.z_bin == 0.0) run.fail("slip", "no 'slip': it has no effect, the runs have no slab profile (profiles.z_bin)");
    if (poiseuille && geometry.z_bin == 0.0) run.fail("poiseuille", "no 'poiseuille': it has no effect, the runs have no slab profile (profiles.z_bin)");
    const FlowResult r = compute_flow(geometry, samples, slip, poiseuille);
    write_tables(run, r);
    if (r.v_mean)
      run.out.scalar({"v_x_mean", r.v_mean->value, r.v_mean->error, "r_c/tau", "mean v_x of all liquid particles (sum over slabs / number)",
                      {{"samples", r.samples}, {"rows", r.rows}}});
    if (slip) write_scalars(run, r, *slip);
    if (poiseuille) write_poiseuille_scalars(run, r, *poiseuille);
  });
}
