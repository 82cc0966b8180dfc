// anisodyn-response: switching response times per trajectory (spec 50 §8.1: t_ON, t_OFF at the
// literal 105% and t_OFF,95%) with modified Z-score outlier rejection over trajectories (§8.2), and
// the replica-mean signal against time since the switch-on.
#include <cstdio>
#include <type_traits>

#include "anisodyn/analysis/per_species_stage.hpp"
#include "anisodyn/analysis/response_times.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

std::vector<double> flags(const std::vector<char>& f) { return std::vector<double>(f.begin(), f.end()); }

void add_time_columns(Table& t, const std::string& name, const std::string& definition, const std::vector<double>& values,
                      const OutlierRejection& o) {
  t.add(name, "tau", definition + " (NaN: threshold never reached)", values);
  t.add(name + "_score", "1", "spec 50 H2: modified Z-score M_j = 0.6745 (t_j - median)/MAD of " + name, o.score);
  t.add(name + "_rejected", "1", "1 if |M_j| > threshold (spec 50 H2 Decision: 3.5), else 0", flags(o.rejected));
  t.add(name + "_flag_one_sided", "1", "1 if M_j > threshold (the one-sided criterion as printed), else 0", flags(o.one_sided));
}

void add_scalar(StageRun& run, const std::string& name, const std::string& species, const std::string& definition,
                const OutlierRejection& o, const ResponseSettings& s, const ResponseResult& r) {
  Scalar sc;
  sc.name = name + "_" + species;
  sc.value = o.retained.value;
  sc.error = o.retained.error;
  sc.units = "tau";
  sc.definition = definition + "; mean +- standard error over the trajectories retained by the modified Z-score (spec 50 H2)";
  sc.details = {{"trajectories", o.score.size()}, {"retained", o.used}, {"rejected", o.rejected_count},
                {"flagged_one_sided", o.one_sided_count}, {"not_reached", o.missing}, {"z_threshold", s.z_threshold},
                {"scale", o.mean_absolute_deviation ? "MAD = 0: 1.253314 x mean absolute deviation" : "MAD / 0.6745"},
                {"signal", r.signal}, {"main_axis", axis_letter(r.main_axis)},
                {"smoothing", "centred moving average over " + std::to_string(s.parameters.smoothing_fraction * 100) +
                                  "% of each segment's frames (Decision)"},
                {"interpolation", "linear between the frames bracketing the threshold"}};
  run.out.scalar(sc);
}

void write_results(StageRun& run, const ResponseSettings& s, const SelectedSpecies& sp, const ResponseResult& r) {
  const std::string sig = r.signal == "B2" ? std::string("B_2,") + axis_letter(r.main_axis) : r.signal;
  Table& t = run.out.table("response_" + sp.name, "response times of species " + sp.name + " per trajectory (spec 50 section 8), signal " + sig);
  using Replica = std::decay_t<decltype(r.replicas.front())>;
  const auto& rows = r.replicas;
  t.add("replica", "1", "index of the input trajectory (order of the inputs)", index_column(rows.size()));
  t.add("switch_on", "tau", "switch-on instant (config switch_on or the field_switches observable)", column_of(rows, &Replica::switch_on));
  t.add("switch_off", "tau", "switch-off instant (NaN: none)", column_of(rows, &Replica::switch_off));
  t.add("signal_on", "1", "spec 50 H1: B_on, mean of " + sig + " over the last 25% of the on-segment", column_of(rows, &Replica::b_on));
  t.add("signal_eq_off", "1", "spec 50 H1: B_eq,off, mean of " + sig + " over the field-off segment before the switch-on",
        column_of(rows, &Replica::b_eq_off));
  t.add("window_on", "frames", "moving-average window of the on-segment (1% of its frames, odd)", column_of(rows, &Replica::window_on));
  t.add("window_off", "frames", "moving-average window of the off-segment (1% of its frames, odd)", column_of(rows, &Replica::window_off));
  add_time_columns(t, "t_on", "spec 50 H1: first time after switch-on with smoothed " + sig + " >= 0.95 B_on",
                   column_of(rows, &Replica::t_on), r.on);
  add_time_columns(t, "t_off", "spec 50 H1: first time after switch-off with smoothed " + sig + " <= 1.05 B_eq,off (literal 105%)",
                   column_of(rows, &Replica::t_off), r.off);
  add_time_columns(t, "t_off95", "spec 50 H1 Decision: first time after switch-off with smoothed " + sig +
                                      " <= B_eq,off + 0.05 (B_on - B_eq,off)", column_of(rows, &Replica::t_off95), r.off95);
  Table& c = run.out.table("response_curve_" + sp.name, "mean " + sig + " of species " + sp.name + " against time since the switch-on");
  c.add("time", "tau", "time since the switch-on: mean over replicas of t_frame - t_switch_on (spec 50 section 0)", r.curve_time);
  c.add("signal", "1", sig + " (spec 50 C1/C2/C4), replicas interpolated linearly onto the common grid", r.curve);
  c.add("signal_se", "1", "standard error over replicas (n - 1; NaN for one replica)", r.curve_se);
  add_scalar(run, "t_on", sp.name, "spec 50 H1: t_ON", r.on, s, r);
  add_scalar(run, "t_off", sp.name, "spec 50 H1: t_OFF at 1.05 B_eq,off (literal reading; the plotted definition)", r.off, s, r);
  add_scalar(run, "t_off95", sp.name, "spec 50 H1 Decision: t_OFF,95% at B_eq,off + 0.05 (B_on - B_eq,off), robust when B_eq,off ~ 0",
             r.off95, s, r);
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-response: %s: t_ON = %.4g ± %.2g (%zu rejected), t_OFF = %.4g ± %.2g, t_OFF95 = %.4g ± %.2g\n",
                 sp.name.c_str(), r.on.retained.value, r.on.retained.error, r.on.rejected_count, r.off.retained.value,
                 r.off.retained.error, r.off95.retained.value, r.off95.retained.error);
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {optional("species", "string", nullptr, "the species to analyse (none: every anisotropic species)"),
       optional("signal", "string", "B2", "B2 | U_L | U_W | U_T | S_cube: the order parameter that responds"),
       optional("main_axis", "string", "auto", "main axis of B2 (signal B2): T | W | L | auto"),
       optional("field_direction", "array", nullptr, "reference direction of S_cube (signal S_cube; none: the run's field)"),
       optional("switch_on", "number", nullptr, "switch-on time (none: each replica's field_switches observable)"),
       optional("switch_off", "number", nullptr, "switch-off time (with switch_on)"),
       optional("cycle", "integer", 0, "which on-off cycle of field_switches to analyse"),
       optional("smoothing_fraction", "number", 0.01, "smoothing window as a fraction of the segment length"),
       optional("outlier_threshold", "number", 3.5, "modified Z-score above which a replica is rejected")},
      "tables response_<species> (per replica) and response_curve_<species>; scalars t_on, t_off, t_off95");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-response", "switching response times t_ON, t_OFF with outlier rejection over trajectories",
                            "See docs/analysis.md.", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const ResponseSettings settings = parse_response_settings(run.cfg);
    run.cfg.finish();
    TrajectoryNeeds needs;
    needs.orientations = true;
    needs.event_observables = {"field_switches"};  // windowed: the switches inside the window
    needs.min_frames = 2;
    run_per_species(
        run, {settings.species, SpeciesScope::Oriented}, needs, [&] { return ResponseAnalysis(settings, run.opt.config_name()); },
        [&](const SelectedSpecies& sp, ResponseAnalysis& a, const std::vector<double>&) { write_results(run, settings, sp, a.compute()); });
  });
}
