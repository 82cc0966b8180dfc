// anisodyn-clusters: cluster analyses of spec 50 §5 over replicas, by `mode`:
//   nematic — nematic-like clusters of HBPs (E1): ⟨N_n⟩, ⟨N_tot⟩, |cos θ| of cluster directors
//             against the box axes, largest-cluster fraction;
//   dipolar — dipolar-energy chains of cubes (E2) with chain statistics X(l,t), X_c, ⟨l⟩_n, ⟨l⟩_w and
//             t_r (E4), transition matrices P(l → l′) (E5) and the Wertheim fit (E6);
//   dbscan  — DBSCAN calibration of βu_max (E3).
#include <cstdio>
#include <sstream>

#include "anisodyn/analysis/dbscan.hpp"
#include "anisodyn/geometry/body_axes.hpp"
#include "anisodyn/analysis/dipolar_clusters.hpp"
#include "anisodyn/analysis/nematic_clusters.hpp"
#include "anisodyn/analysis/per_species_stage.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

std::string factor_name(double f) {
  std::ostringstream o;
  o << f;
  std::string s = o.str();
  for (char& c : s)
    if (c == '.') c = 'p';
  return s;
}

// ---- nematic --------------------------------------------------------------------------------------

void write_nematic(StageRun& run, const NematicClusterSettings& s, const SelectedSpecies& sp, const NematicClusterResult& r) {
  const std::string rule = kNematicClusterRule;
  const nlohmann::json details = {{"rule_version", rule}, {"species", sp.name}, {"axis", body_axis_name(s.axis)},
                                  {"K1", s.k1}, {"K2", s.k2}, {"K_par", s.k_par}, {"K_perp", s.k_perp},
                                  {"configurations", r.configurations}, {"error_samples", r.samples},
                                  {"error", run.inputs.size() > 1 ? "standard error over replicas" : "standard error over <= 10 blocks of configurations"},
                                  {"unconverged_configurations", r.unconverged}};

  Table& sizes = run.out.table("nematic_cluster_sizes", "spec 50 E1: cluster-size histogram <N_n> (" + rule + ")");
  sizes.add("n", "1", "cluster size n (particles)", r.size);
  sizes.add("mean_count", "1", "spec 50 E1: <N_n>, mean number of clusters of size n per configuration", r.mean_count);
  sizes.add("mean_count_se", "1", "standard error of mean_count", r.mean_count_error);

  Table& cosines = run.out.table("nematic_director_cos", "spec 50 E1: distribution of |cos theta| between the directors of clusters with n >= 2 and the box axes (long format)");
  std::vector<double> axis, centre, density, density_se;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t b = 0; b < r.cos_center.size(); ++b) {
      axis.push_back(static_cast<double>(k));
      centre.push_back(r.cos_center[b]);
      density.push_back(r.cos_density[k][b]);
      density_se.push_back(r.cos_density_error[k][b]);
    }
  cosines.add("box_axis", "1", "box axis a: 0 x, 1 y, 2 z", axis);
  cosines.add("cos_abs", "1", "bin centre of |n_local . e_a|", centre);
  cosines.add("density", "1", "probability density of |cos theta| over clusters with n >= 2 (integrates to 1 over [0, 1])", density);
  cosines.add("density_se", "1", "standard error of density", density_se);

  Table& configs = run.out.table("nematic_configurations", "per configuration: clusters and convergence of the E1 algorithm");
  Table& clusters = run.out.table("nematic_clusters", "per configuration: every cluster with n >= 2, its size and director n_local (long format)");
  std::vector<double> c_rep, c_frame, c_time, c_total, c_largest, c_frac, c_passes, c_conv;
  std::vector<double> k_rep, k_frame, k_size, k_x, k_y, k_z, k_u;
  for (const auto& c : r.per_configuration) {
    c_rep.push_back(static_cast<double>(c.replica));
    c_frame.push_back(static_cast<double>(c.frame));
    c_time.push_back(c.time);
    c_total.push_back(static_cast<double>(c.clusters));
    c_largest.push_back(static_cast<double>(c.largest));
    c_frac.push_back(static_cast<double>(c.largest) / static_cast<double>(c.particles));
    c_passes.push_back(c.passes);
    c_conv.push_back(c.converged ? 1.0 : 0.0);
    for (std::size_t k = 0; k < c.multi_size.size(); ++k) {
      k_rep.push_back(static_cast<double>(c.replica));
      k_frame.push_back(static_cast<double>(c.frame));
      k_size.push_back(static_cast<double>(c.multi_size[k]));
      k_x.push_back(c.multi_director[k].x());
      k_y.push_back(c.multi_director[k].y());
      k_z.push_back(c.multi_director[k].z());
      k_u.push_back(c.multi_order[k]);
    }
  }
  configs.add("replica", "1", "replica index (input order)", c_rep);
  configs.add("frame", "1", "frame index in the replica", c_frame);
  configs.add("time", "tau", "frame time", c_time);
  configs.add("clusters", "1", "N_tot: number of clusters (singletons included)", c_total);
  configs.add("largest", "1", "size of the largest cluster", c_largest);
  configs.add("largest_fraction", "1", "largest cluster size / number of particles of the species", c_frac);
  configs.add("passes", "1", "passes of steps 2-5 of the E1 algorithm", c_passes);
  configs.add("converged", "1", "1 if the last pass changed nothing (else the 20-pass limit was hit)", c_conv);
  clusters.add("replica", "1", "replica index", k_rep);
  clusters.add("frame", "1", "frame index", k_frame);
  clusters.add("size", "1", "cluster size n >= 2", k_size);
  clusters.add("director_x", "1", "x of the cluster director n_local (largest-eigenvalue eigenvector of its Q tensor)", k_x);
  clusters.add("director_y", "1", "y of n_local", k_y);
  clusters.add("director_z", "1", "z of n_local", k_z);
  clusters.add("order", "1", "U_local, largest eigenvalue of the cluster's Q tensor of the relevant axis", k_u);

  run.out.scalar({"N_tot", r.total.value, r.total.error, "1", "spec 50 E1: <N_tot>, mean number of clusters per configuration (singletons included)", details});
  run.out.scalar({"largest_cluster_fraction", r.largest_fraction.value, r.largest_fraction.error, "1",
                  "spec 50 E1 calibration: mean fraction of the particles in the largest cluster (>= 0.95 expected in N_U at eta = 0.34)", details});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-clusters: nematic %s: <N_tot> = %.5g ± %.2g, largest fraction %.4f over %zu configurations (%zu unconverged)\n",
                 sp.name.c_str(), r.total.value, r.total.error, r.largest_fraction.value, r.configurations, r.unconverged);
}

void run_nematic(StageRun& run) {
  const NematicClusterSettings s = parse_nematic_cluster_settings(run.cfg);
  run.cfg.finish();
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.orientations = true;
  run_per_species(
      run, {s.species, SpeciesScope::Single}, needs, [&] { return NematicClusterAnalysis(s, run.inputs.size(), run.opt.config_name()); },
      [&](const SelectedSpecies& sp, NematicClusterAnalysis& a, const std::vector<double>&) { write_nematic(run, s, sp, a.compute()); });
}

// ---- dipolar --------------------------------------------------------------------------------------

void write_dipolar(StageRun& run, const DipolarClusterSettings& s, const SelectedSpecies& sp, const DipolarChainResult& r) {
  const nlohmann::json rule = {{"species", sp.name}, {"gamma", s.rule.gamma}, {"sigma", s.rule.sigma}, {"bu_max", s.rule.bu_max},
                               {"field_direction", {s.rule.field.x(), s.rule.field.y(), s.rule.field.z()}},
                               {"replicas", r.replicas}, {"cubes", r.cubes},
                               {"time_grid", "mean time stamp of each frame over replicas, replicas linearly interpolated onto it (spec 50 section 0)"}};
  const std::size_t F = r.time.size(), L = r.sizes;
  const std::string lump = s.max_chain_length > 0 ? "; the last class l = max_chain_length holds all sizes >= it" : "";

  Table& x = run.out.table("chain_size_fractions", "spec 50 E4: X(l, t) = N(l, t)/N_cube, bonds beta u_ij < beta u_max (E2), long format" + lump);
  std::vector<double> xt, xl, xv, xe;
  for (std::size_t f = 0; f < F; ++f)
    for (std::size_t l = 0; l < L; ++l) {
      xt.push_back(r.time[f]);
      xl.push_back(static_cast<double>(l + 1));
      xv.push_back(r.x[f * L + l]);
      xe.push_back(r.x_error[f * L + l]);
    }
  x.add("time", "tau", "time since the field switch (common grid)", xt);
  x.add("l", "1", "cluster size l (1 = free cube)", xl);
  x.add("X", "1", "spec 50 E4: X(l, t) = N(l, t)/N_cube, mean over replicas", xv);
  x.add("X_se", "1", "standard error of X over replicas", xe);

  Table& st = run.out.table("chain_statistics", "spec 50 E4: chain statistics against time, mean over replicas");
  st.add("time", "tau", "time since the field switch (common grid)", r.time);
  st.add("X_c", "1", "spec 50 E4: X_c(t) = sum_{l>=2} l X(l, t), fraction of cubes in chains", r.chain_fraction);
  st.add("X_c_se", "1", "standard error of X_c over replicas", r.chain_fraction_error);
  st.add("l_n", "1", "spec 50 E4: <l>_n = sum_{l>=2} l N(l) / sum_{l>=2} N(l) (replica mean; replicas without chains skipped)", r.mean_length);
  st.add("l_n_se", "1", "standard error of l_n over replicas", r.mean_length_error);
  st.add("l_w", "1", "spec 50 E4: <l>_w = sum_{l>=2} l^2 N(l) / sum_{l>=2} l N(l) (replica mean)", r.weight_mean_length);
  st.add("l_w_se", "1", "standard error of l_w over replicas", r.weight_mean_length_error);

  nlohmann::json plateau = rule;
  plateau["plateau_window"] = {r.plateau_t_min, F ? r.time.back() : 0.0};
  plateau["plateau_fraction"] = s.plateau_fraction;
  plateau["method"] = "mean of X_c over the last plateau_fraction of the run; error by jackknife over replicas";
  run.out.scalar({"X_c_plateau", r.plateau.value, r.plateau.error, "1", "spec 50 E4: plateau of X_c(t), mean over the last 25% (plateau_fraction) of the field-on segment", plateau});
  plateau["method"] = "first time X_c(t) >= 0.95 plateau, linear interpolation between frames; error by jackknife over replicas";
  run.out.scalar({"response_time", r.response_time.value, r.response_time.error, "tau",
                  "spec 50 E4 Decision: t_r, first time at which X_c(t) reaches 95% of its plateau", plateau});

  Table& tm = run.out.table("transition_matrix", "spec 50 E5: P(l -> l'), per cube, pooled over t_1 +- window and replicas, rows normalised; P < 1e-6 written as NaN (blank)" + lump);
  std::vector<double> t1, tl, tlp, tp, tpe, trow;
  for (std::size_t k = 0; k < r.transitions.size(); ++k) {
    const TransitionMatrix& m = r.transitions[k];
    for (std::size_t a = 0; a < m.sizes; ++a)
      for (std::size_t b = 0; b < m.sizes; ++b) {
        t1.push_back(m.t1);
        tl.push_back(static_cast<double>(a + 1));
        tlp.push_back(static_cast<double>(b + 1));
        tp.push_back(m.probability[a * m.sizes + b]);
        tpe.push_back(m.error[a * m.sizes + b]);
        trow.push_back(m.row_count[a]);
      }
    nlohmann::json d = rule;
    d.update({{"source", m.source}, {"lag", s.transition_lag}, {"window", s.transition_window},
              {"pooled_t1_frames", {m.window_min, m.window_max}}, {"frame_pairs", m.frame_pairs},
              {"lag_tolerance", s.lag_tolerance}});
    run.out.scalar({"transition_t1_" + std::to_string(k), m.t1, 0.0, "tau", "spec 50 E5: t_1 of transition matrix " + std::to_string(k) + " (" + m.source + ")", d});
  }
  tm.add("t1", "tau", "requested t_1 (frames within +-window t_1 pooled)", t1);
  tm.add("l", "1", "cluster size l of the cube at t_1", tl);
  tm.add("l_prime", "1", "cluster size l' of the same cube at t_1 + lag", tlp);
  tm.add("probability", "1", "spec 50 E5: P(l -> l') = count(l, l') / sum_l' count(l, l'); NaN if < 1e-6 or row empty", tp);
  tm.add("probability_se", "1", "jackknife standard error over replicas", tpe);
  tm.add("row_count", "1", "cubes counted in row l (pooled over frames and replicas)", trow);

  const WertheimFit& w = r.wertheim;
  Table& wt = run.out.table("wertheim_fit", "spec 50 E6: fit of the stationary X(l) by X_eq(l) = (1 - p_b)^2 p_b^(l-1), l >= 1, weights 1/Var");
  wt.add("l", "1", "cluster size l", w.length);
  wt.add("X", "1", "stationary X(l): mean over the plateau window and replicas", w.value);
  wt.add("variance", "1", "Var of the mean X(l) (squared standard error over replicas)", w.variance);
  wt.add("weight", "1", "fit weight 1/Var", w.weight);
  wt.add("model", "1", "X_eq(l) at the fitted p_b", w.model);
  wt.add("residual", "1", "X - X_eq", w.residual);
  wt.add("normalised_residual", "1", "(X - X_eq)/sqrt(Var)", w.normalised_residual);
  nlohmann::json wd = rule;
  wd.update({{"method", w.method}, {"fit_window_l", {1, w.length.size()}}, {"plateau_window", {r.plateau_t_min, F ? r.time.back() : 0.0}},
             {"chi2", w.chi2}, {"error_curvature", w.error_curvature}, {"minimiser", "400-point scan then golden section on (0, 1)"}});
  run.out.scalar({"wertheim_p_b", w.p_b, w.error, "1", "spec 50 E6: bond probability p_b of X_eq(l) = (1 - p_b)^2 p_b^(l-1)", wd});
  if (!run.opt.quiet)
    std::fprintf(stderr, "anisodyn-clusters: dipolar %s: X_c plateau %.4f ± %.2g, t_r = %.4g ± %.2g, p_b = %.4f ± %.2g\n", sp.name.c_str(),
                 r.plateau.value, r.plateau.error, r.response_time.value, r.response_time.error, w.p_b, w.error);
}

void run_dipolar(StageRun& run) {
  const DipolarClusterSettings s = parse_dipolar_cluster_settings(run.cfg);
  run.cfg.finish();
  TrajectoryNeeds needs;
  needs.positions = true;
  needs.min_frames = 2;  // a time series
  run_per_species(
      run, {s.species, SpeciesScope::Single}, needs, [&] { return DipolarChainAnalysis(s, run.opt.config_name()); },
      [&](const SelectedSpecies& sp, DipolarChainAnalysis& a, const std::vector<double>&) {
        if (s.transition_at_x2_maximum) {  // a second pass: t_1 is known only once every replica is in
          const double t1 = a.time_of_x2_maximum();
          run.each_replica(needs, [&](const Trajectory& t, std::size_t) { a.accumulate_transitions(t, sp.index, t1, "maximum of X(2,t)"); });
        }
        write_dipolar(run, s, sp, a.compute());
      });
}

// ---- dbscan ---------------------------------------------------------------------------------------

void write_dbscan(StageRun& run, const DbscanCalibrationSettings& s, const SelectedSpecies& sp, const DbscanCalibrationResult& r) {
  const std::string knee = s.eps ? "given" : "knee of the sorted k-NN distance curve (k = MinPts, self excluded): the point farthest below the chord between its ends, both axes scaled to [0, 1]";
  const nlohmann::json details = {{"species", sp.name}, {"gamma", s.rule.gamma}, {"sigma", s.rule.sigma},
                                  {"field_direction", {s.rule.field.x(), s.rule.field.y(), s.rule.field.z()}},
                                  {"min_pts", s.min_pts}, {"eps_rule", knee}, {"r_max", s.r_max},
                                  {"cluster_choice", "DBSCAN cluster whose centroid is nearest (sigma, 0)"},
                                  {"configurations", r.configurations.size()}};
  std::vector<double> rep, frame, time, points, factor, eps, clusters, noise, cpts, bu;
  for (const auto& c : r.configurations)
    for (std::size_t k = 0; k < c.per_factor.size(); ++k) {
      const BondCalibration& b = c.per_factor[k];
      rep.push_back(static_cast<double>(c.replica));
      frame.push_back(static_cast<double>(c.frame));
      time.push_back(c.time);
      points.push_back(static_cast<double>(c.points));
      factor.push_back(s.eps_factors[k]);
      eps.push_back(b.eps);
      clusters.push_back(b.clusters);
      noise.push_back(static_cast<double>(b.noise));
      cpts.push_back(static_cast<double>(b.cluster_points));
      bu.push_back(b.bu_max);
    }
  Table& t = run.out.table("dbscan_configurations", "spec 50 E3: DBSCAN of the (r_par, r_perp) nearest-neighbour points of each configuration (long format over Eps factors)");
  t.add("replica", "1", "replica index (input order)", rep);
  t.add("frame", "1", "frame index", frame);
  t.add("time", "tau", "frame time", time);
  t.add("points", "1", "(r_par, r_perp) points after removing duplicate pairs and keeping r_par, r_perp <= r_max", points);
  t.add("eps_factor", "1", "factor applied to the base Eps", factor);
  t.add("eps", "length", "Eps used (base Eps x factor)", eps);
  t.add("clusters", "1", "DBSCAN clusters found", clusters);
  t.add("noise", "1", "points labelled noise", noise);
  t.add("cluster_points", "1", "points of the kept cluster (nearest (sigma, 0))", cpts);
  t.add("bu_max", "kT", "spec 50 E3: max of beta u(r_par, r_perp) over the kept cluster (NaN if none)", bu);
  for (std::size_t k = 0; k < r.eps_factors.size(); ++k) {
    nlohmann::json d = details;
    d["eps_factor"] = r.eps_factors[k];
    d["configurations_with_cluster"] = r.used[k];
    run.out.scalar({"bu_max_eps_x" + factor_name(r.eps_factors[k]), r.bu_max[k].value, r.bu_max[k].error, "kT",
                    "spec 50 E3: beta u_max averaged over configurations (SE over configurations), Eps x " + d["eps_factor"].dump(), d});
  }
  run.out.scalar({"dbscan_eps", r.base_eps.value, r.base_eps.error, "length", "spec 50 E3 Decision: base Eps, mean over configurations", details});
  if (!run.opt.quiet)
    for (std::size_t k = 0; k < r.eps_factors.size(); ++k)
      std::fprintf(stderr, "anisodyn-clusters: dbscan %s: Eps x %g: beta u_max = %.4g ± %.2g (%zu configurations)\n", sp.name.c_str(),
                   r.eps_factors[k], r.bu_max[k].value, r.bu_max[k].error, r.used[k]);
}

void run_dbscan(StageRun& run) {
  const DbscanCalibrationSettings s = parse_dbscan_settings(run.cfg);
  run.cfg.finish();
  TrajectoryNeeds needs;
  needs.positions = true;
  run_per_species(
      run, {s.species, SpeciesScope::Single}, needs, [&] { return DbscanCalibration(s, run.opt.config_name()); },
      [&](const SelectedSpecies& sp, DbscanCalibration& a, const std::vector<double>&) { write_dbscan(run, s, sp, a.compute()); });
}

tool::Description description() {
  using tool::optional;
  return analysis_description(
      {tool::required("mode", "string", "nematic | dipolar | dbscan"),
       optional("species", "string", nullptr, "the species to cluster (none: the only species of the file)"),
       optional("axis", "string", nullptr, "nematic (required there): body axis T | W | L"),
       optional("K1", "number", 0.85, "nematic: |e_i.e_j| > K1"),
       optional("K2", "number", 0.90, "nematic: U_local > K2"),
       optional("K_par", "number", nullptr, "nematic (required there): |r_par| < K_par"),
       optional("K_perp", "number", nullptr, "nematic (required there): |r_perp| < K_perp"),
       optional("cos_bins", "integer", 20, "nematic: bins of |cos theta| of cluster directors"),
       optional("gamma", "number", nullptr, "dipolar, dbscan (required there): dipolar coupling"),
       optional("sigma", "number", 1.0, "dipolar, dbscan: cube edge"),
       optional("bu_max", "number", -3.20, "dipolar: bond threshold beta u_ij < bu_max"),
       optional("field_direction", "array", nlohmann::json::array({0, 0, 1}), "dipolar, dbscan: the field direction"),
       optional("transition_times", "array", nullptr, "dipolar: times t_1 of transition matrices"),
       optional("transition_at_x2_maximum", "boolean", false, "dipolar: also a transition matrix at the maximum of X(2, t)"),
       optional("transition_lag", "number", 0.3, "dipolar: lag of transition matrices"),
       optional("transition_window", "number", 0.05, "dipolar: frames within +- this fraction of t_1 are pooled"),
       optional("transition_lag_tolerance", "number", 0.1, "dipolar: relative tolerance of the lag between frames"),
       optional("plateau_fraction", "number", 0.25, "dipolar: last fraction of the run that is the X_c plateau"),
       optional("max_chain_length", "integer", 0, "dipolar: size class that holds all longer chains (0: none)"),
       optional("min_pts", "integer", 10, "dbscan: MinPts"),
       optional("eps", "number", nullptr, "dbscan: Eps (none: the knee of the sorted k-NN distances)"),
       optional("r_max", "number", nullptr, "dbscan: neighbour search radius (none: 2 sigma)"),
       optional("eps_factors", "array", nlohmann::json::array({0.7, 1, 1.4}), "dbscan: factors of Eps")},
      "by mode: nematic cluster sizes and directors, dipolar chain statistics, transition matrices and the Wertheim fit, "
      "or the DBSCAN bond thresholds");
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{
      "anisodyn-clusters", "cluster analyses: nematic-like HBP clusters, dipolar chains of cubes, DBSCAN calibration of the bond threshold",
      "Each mode reads only its own keys (docs/analysis.md).", description()};
  return run_analysis_stage(argc, argv, info, [](StageRun& run) {
    const std::string mode = run.cfg.choice("mode", {"nematic", "dipolar", "dbscan"});
    if (mode == "nematic") run_nematic(run);
    if (mode == "dipolar") run_dipolar(run);
    if (mode == "dbscan") run_dbscan(run);
  });
}
