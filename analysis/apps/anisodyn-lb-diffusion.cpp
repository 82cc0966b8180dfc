// anisodyn-lb-diffusion: the diffusion of a free raspberry in anisodyn-lb's thermal fluid (spec 40
// §8.1–8.4, studies D2b, D3, D4): lab-frame D_t and its Hasimoto-corrected value, the rotational D_r
// of the reference bead's vector (⟨ΔΘ²⟩/(4τ); the paper's 6τ with rotation_convention "paper"), the
// three-axis mean D̄_r, and the body-frame D_t,i and D_r,i (quaternion projection); frictions kT/D in
// water units (the friction scale of spec 40 §1.1) and reduced by 6πηR and 8πηR³. Replicas are the
// independent runs at one box size; errors are the jackknife over them.
#include <cmath>
#include <functional>
#include <optional>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/raspberry_diffusion.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/lb_run_summary.hpp"
#include "anisodyn/analysis/stage.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

constexpr double kHasimoto = 2.837297;  // spec 40 §8.1

tool::Description description() {
  return analysis_description(
      {tool::optional("fit", "object", nullptr,
                      "{t_min, t_max}: the lag window of the translational fits (default: spec 40 §8.1's 0.5 ... 2 L^2/nu, L the box edge)"),
       tool::optional("rotation_fit_fraction", "number", 0.1, "rotational fits over lags tau <= this / (2 D_r), the window found by iterating once"),
       tool::optional("rotation_convention", "string", "default",
                      "default (D_r = <dTheta^2>/(4 tau), body axes /(2 tau)) | paper (6 tau, and 3 tau for the body axes: 2/3 of the true D_r)")},
      "tables lag_curves (per lag: lab MSD, reference-vector and three-axis angle MSDs, body-frame MSDs per axis, with errors); scalars D_t, "
      "D_t_hasimoto, D_r, D_r_three_axis, D_t_body_x/y/z, D_r_body_x/y/z, their ratios and frictions in water units, alpha and the run's stability number");
}

/// What the run's parameters and summary say: its fluid, units, body and reference bead.
struct RunFacts {
  double kT = 1.0, eta = 0.0, nu = 0.0, friction_scale = 1.0, box = 0.0, radius = 0.0;
  Vec3 semi_axes = Vec3::Zero(), reference = Vec3::Zero();
  double reference_angle = 0.0;
  double stability = 0.0;  // dt * sum(xi_bead) / m of the run (spec 40 §4)
};

RunFacts run_facts(const std::string& path) {
  const io::H5mdReader reader(path);
  const nlohmann::json provenance = reader.provenance();
  if (!provenance.contains("units")) throw InputError(path, "/parameters/provenance", "an anisodyn-lb run (its provenance has no units)");
  const nlohmann::json& units = provenance.at("units");
  const LbRunSummary run = read_lb_run_summary(reader, path);
  const nlohmann::json& summary = run.summary;
  if (summary.at("raspberries").at("fixed").get<bool>()) throw InputError(path, "/parameters/config", "free raspberries (this run holds them fixed)");
  if (!(summary.at("kT").get<double>() > 0.0)) throw InputError(path, "/parameters/config", "a thermal run (fluid.thermal true): no noise, no diffusion");
  const nlohmann::json& body = run.body;
  RunFacts f;
  f.kT = summary.at("kT").get<double>();
  f.nu = units.at("simulated_kinematic_viscosity").get<double>();
  f.eta = units.at("simulated_dynamic_viscosity").get<double>();
  f.friction_scale = units.at("friction_scale").get<double>();
  const auto v = [](const nlohmann::json& j) { return Vec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()); };
  f.semi_axes = v(body.at("semi_axes"));
  f.reference = v(body.at("reference_offset"));
  f.reference_angle = body.at("reference_angle").get<double>();
  f.stability = body.at("stability").get<double>();
  f.radius = std::cbrt(f.semi_axes.prod());
  const State first = reader.read_frame(0);
  const Vec3 edges = first.box.edges();
  if (edges.maxCoeff() - edges.minCoeff() > 1e-9 * edges.maxCoeff())
    throw InputError(path, "/particles/all/box", "a cubic box (the Hasimoto correction of spec 40 §8.1 is for cubic boxes)");
  f.box = edges.x();
  return f;
}

/// The slope of y over the lags t_k with t_min <= t_k <= t_max: with an intercept (translation), or
/// through the origin (rotation, whose angles start at 0).
double slope(const std::vector<double>& lag, const std::vector<double>& y, double t_min, double t_max, bool through_origin) {
  std::vector<double> x, yy;
  for (std::size_t k = 0; k < lag.size(); ++k)
    if (lag[k] >= t_min * (1 - 1e-9) && lag[k] <= t_max * (1 + 1e-9)) x.push_back(lag[k]), yy.push_back(y[k]);
  return through_origin ? fit_proportional(x, yy).slope : fit_line(x, yy).slope;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-lb-diffusion", "Diffusion of a free raspberry: lab and body frame (spec 40 §8)", "See docs/lb.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    std::optional<std::pair<double, double>> window;
    if (auto fit = run.cfg.optional_object("fit")) {
      window = std::pair{fit->positive("t_min"), fit->positive("t_max")};
      if (!(window->first < window->second)) fit->fail("t_max", "expected t_max above t_min");
    }
    const double fraction = run.cfg.positive("rotation_fit_fraction", 0.1);
    const bool paper = run.cfg.choice("rotation_convention", {"default", "paper"}, "default") == "paper";
    run.cfg.finish();

    const RunFacts facts = run_facts(run.inputs.front());
    for (std::size_t k = 1; k < run.inputs.size(); ++k) {
      const RunFacts other = run_facts(run.inputs[k]);
      if (std::abs(other.box - facts.box) > 1e-9 || (other.semi_axes - facts.semi_axes).norm() > 1e-9 || std::abs(other.nu - facts.nu) > 1e-12 ||
          std::abs(other.friction_scale - facts.friction_scale) > 1e-12)
        throw InputError(run.inputs[k], "/parameters", "the same box, body and fluid as " + run.inputs.front() + " (replicas of one system)");
    }
    const double t_min = window ? window->first : 0.5 * facts.box * facts.box / facts.nu;
    const double t_max = window ? window->second : 2.0 * facts.box * facts.box / facts.nu;

    CurveSamples samples;
    std::vector<double> lag;
    TrajectoryNeeds needs;
    needs.positions = needs.orientations = true;
    needs.window = run.window;
    needs.min_frames = 3;
    run.each_replica(needs, [&](const Trajectory& tr, std::size_t) {
      if (tr.particles != 1) throw InputError(tr.path, "/particles/all", "one raspberry per run (spec 40 §7.1)");
      const double spacing = tr.time[1] - tr.time[0];
      for (std::size_t f = 1; f < tr.frames; ++f)
        if (std::abs(tr.time[f] - tr.time[f - 1] - spacing) > 1e-6 * spacing)
          throw InputError(tr.path, "/particles/all/position/time", "frames at a uniform spacing (frames.every_steps)");
      const auto max_lag = static_cast<std::size_t>(std::floor(t_max / spacing + 1e-9));
      if (max_lag >= tr.frames)
        run.fail(window ? "fit.t_max" : "fit", "expected the translational fit window (up to " + std::to_string(t_max) + " t0" +
                                                   (window ? "" : ", spec 40's 2 L^2/nu") + ") within the trajectory's span of " +
                                                   std::to_string(tr.time.back() - tr.time.front()) + " t0 in " + tr.path);
      std::vector<Vec3> centre;
      std::vector<Quat> orientation;
      for (std::size_t f = 0; f < tr.frames; ++f) centre.push_back(tr.pos(f, 0)), orientation.push_back(tr.quat(f, 0));
      if (lag.empty())
        for (std::size_t k = 1; k <= max_lag; ++k) lag.push_back(static_cast<double>(k) * spacing);
      if (lag.size() != max_lag) throw InputError(tr.path, "/particles/all", "the frame spacing of the other runs");
      samples.add(body_lag_curves(centre, orientation, facts.reference, max_lag).flatten());
    });

    // The rotational window from the mean curve: the first lags, then lags up to fraction/(2 D_r), twice.
    const BodyLagCurves mean = BodyLagCurves::unflatten(samples.mean());
    double rotation_max = lag[std::min<std::size_t>(lag.size(), 10) - 1];
    for (int pass = 0; pass < 2; ++pass) {
      const double dr = slope(lag, mean.vector_angle, 0.0, rotation_max, true) / 4.0;
      rotation_max = std::min(lag.back(), std::max(lag.front(), fraction / (2.0 * dr)));
    }
    const double rotation_divisor = paper ? 6.0 : 4.0, axis_divisor = paper ? 3.0 : 2.0;
    struct Quantity {
      std::string name, units, definition;
      std::function<double(const BodyLagCurves&)> value;
    };
    const auto trans = [&](const std::vector<double>& y) { return slope(lag, y, t_min, t_max, false); };
    const auto rot = [&](const std::vector<double>& y) { return slope(lag, y, 0.0, rotation_max, true); };
    const double hasimoto = kHasimoto * facts.kT / (6.0 * M_PI * facts.eta * facts.box);
    const double six_pi_eta_r = 6.0 * M_PI * facts.eta * facts.radius, eight_pi_eta_r3 = 8.0 * M_PI * facts.eta * std::pow(facts.radius, 3);
    const std::string conv = paper ? " (paper convention: 2/3 of the true value)" : "";
    std::vector<Quantity> quantities = {
        {"D_t", "sigma^2/t0", "lab-frame MSD slope / 6 over the translational window (run's units)", [&](const BodyLagCurves& c) { return trans(c.lab) / 6.0; }},
        {"D_t_hasimoto", "sigma^2/t0", "D_t + 2.837297 kT/(6 pi eta L): the box-size-corrected D_t of one box (spec 40 §8.1)",
         [&](const BodyLagCurves& c) { return trans(c.lab) / 6.0 + hasimoto; }},
        {"D_r", "1/t0", "reference-vector angle MSD slope / " + std::string(paper ? "6" : "4") + " over the rotational window" + conv,
         [&](const BodyLagCurves& c) { return rot(c.vector_angle) / rotation_divisor; }},
        {"D_r_three_axis", "1/t0", "sum over the body axes of their angle MSD, slope / 12: the mean D_r over the axes", [&](const BodyLagCurves& c) { return rot(c.axes_angle) / 12.0; }},
    };
    const char* axis_name[3] = {"x", "y", "z"};
    for (std::size_t i = 0; i < 3; ++i) {
      quantities.push_back({std::string("D_t_body_") + axis_name[i], "sigma^2/t0", std::string("body-frame MSD along body ") + axis_name[i] + ", slope / 2 over the translational window",
                            [&, i](const BodyLagCurves& c) { return trans(c.body_translation[i]) / 2.0; }});
      quantities.push_back({std::string("D_r_body_") + axis_name[i], "1/t0", std::string("body-frame angle MSD about body ") + axis_name[i] + " (projection method), slope / " + (paper ? "3" : "2") + conv,
                            [&, i](const BodyLagCurves& c) { return rot(c.body_rotation[i]) / axis_divisor; }});
    }
    quantities.push_back({"D_t_axial_over_perp", "1", "D_t_body_x / mean(D_t_body_y, D_t_body_z): body x is a spheroid's symmetry axis",
                          [&](const BodyLagCurves& c) { return 2.0 * trans(c.body_translation[0]) / (trans(c.body_translation[1]) + trans(c.body_translation[2])); }});
    quantities.push_back({"D_r_axial_over_perp", "1", "D_r_body_x / mean(D_r_body_y, D_r_body_z)",
                          [&](const BodyLagCurves& c) { return 2.0 * rot(c.body_rotation[0]) / (rot(c.body_rotation[1]) + rot(c.body_rotation[2])); }});
    quantities.push_back({"xi_t_water", "M0/t0", "kT / D_t in water units (divided by the friction scale s, spec 40 §1.1)",
                          [&](const BodyLagCurves& c) { return facts.kT / (trans(c.lab) / 6.0) / facts.friction_scale; }});
    quantities.push_back({"xi_r_water", "M0 sigma^2/t0", "kT / D_r in water units", [&](const BodyLagCurves& c) { return facts.kT / (rot(c.vector_angle) / rotation_divisor) / facts.friction_scale; }});
    quantities.push_back({"xi_t_over_6pi_eta_R", "1", "kT / (D_t 6 pi eta R), R = (a b c)^(1/3): the Stokes ratio of the box (not extrapolated)",
                          [&](const BodyLagCurves& c) { return facts.kT / (trans(c.lab) / 6.0) / six_pi_eta_r; }});
    quantities.push_back({"xi_r_over_8pi_eta_R3", "1", "kT / (D_r 8 pi eta R^3): the Stokes-Einstein-Debye ratio",
                          [&](const BodyLagCurves& c) { return facts.kT / (rot(c.vector_angle) / rotation_divisor) / eight_pi_eta_r3; }});

    const nlohmann::json details = {{"runs", samples.count()}, {"error", "jackknife over runs"}, {"translation_window", {t_min, t_max}},
                                    {"rotation_window", {0.0, rotation_max}}, {"box", facts.box}, {"radius", facts.radius},
                                    {"semi_axes", {facts.semi_axes.x(), facts.semi_axes.y(), facts.semi_axes.z()}},
                                    {"kT", facts.kT}, {"eta", facts.eta}, {"friction_scale", facts.friction_scale}, {"reference_angle", facts.reference_angle},
                                    {"rotation_convention", paper ? "paper" : "default"}};
    for (const Quantity& q : quantities) {
      const Estimate e = jackknife(samples, [&](const std::vector<double>& flat) { return q.value(BodyLagCurves::unflatten(flat)); });
      run.out.scalar({q.name, e.value, e.error, q.units, q.definition, details});
    }
    run.out.scalar({"alpha", facts.reference_angle, 0.0, "rad", "the reference bead's polar angle from the body symmetry axis (body x)", details});
    run.out.scalar({"stability", facts.stability, 0.0, "1", "dt * sum(xi_bead) / m of the run (spec 40 §4; the explicit coupling is stable at <= 1)", details});

    Table& t = run.out.table("lag_curves", "spec 40 §8: mean squares per lag over every origin, mean over the runs");
    t.add("lag", "t0", "lag time", lag);
    const auto se = samples.standard_error();
    const std::size_t n = lag.size();
    const auto slice = [&](const std::vector<double>& v, std::size_t k) { return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(k * n), v.begin() + static_cast<std::ptrdiff_t>((k + 1) * n)); };
    const auto flat_mean = samples.mean();
    const char* names[BodyLagCurves::kCurves] = {"msd_lab", "angle2_reference", "angle2_three_axes", "msd_body_x", "msd_body_y", "msd_body_z",
                                                 "angle2_body_x", "angle2_body_y", "angle2_body_z"};
    for (std::size_t k = 0; k < BodyLagCurves::kCurves; ++k) {
      const bool angle = k == 1 || k == 2 || k >= 6;
      t.add(names[k], angle ? "rad^2" : "sigma^2", std::string("mean square of ") + names[k], slice(flat_mean, k));
      t.add(std::string(names[k]) + "_se", angle ? "rad^2" : "sigma^2", "its standard error over the runs", slice(se, k));
    }
  });
}
