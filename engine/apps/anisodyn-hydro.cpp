// anisodyn-hydro: infinite-dilution diffusion tensors of rigid particles from shell models
// (RPY mobility with overlap correction, 6×6 resistance, centre of diffusion, extrapolation to zero
// bead size). Writes a species file (JSON, or HDF5 for a .h5 output) that anisodyn-config and
// anisodyn-dmc read through "diffusion_from". See docs/hydro.md.
#include <cstdio>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/diffusion_tensor.hpp"
#include "anisodyn/hydro/hydro_config.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/command_line.hpp"
#include "anisodyn/tool/provenance.hpp"
#include "anisodyn/io/species_file.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace anisodyn;
using namespace anisodyn::hydro;

namespace {

std::string format_percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g%%", 100.0 * fraction);
  return buf;
}

nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json to_json(const Mat6& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 6; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < 6; ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

/// The default construction keeps its original wording; the fit used is named in it, and under
/// "auto" that it was chosen by its smaller error estimate.
std::string method_of(const HydroSpeciesJob& job, const DiffusionTensorResult& r) {
  std::string method = std::string("shell model, RPY mobility with overlap correction, resistance about the centre of "
                                   "diffusion extrapolated ") +
                       (r.extrapolation == ExtrapolationOrder::Linear ? "linearly" : "quadratically") +
                       " to zero bead radius";
  if (job.extrapolation == ExtrapolationRule::Auto)
    method += " (extrapolation auto: the fit with the smaller error estimate, linear " +
              format_percent(r.relative_error_of(ExtrapolationOrder::Linear).maxCoeff()) + " vs quadratic " +
              format_percent(r.relative_error_of(ExtrapolationOrder::Quadratic).maxCoeff()) + ")";
  if (job.construction != &shell_beads) method += "; shell construction " + job.construction_name;
  return method;
}

nlohmann::json species_entry(const HydroSpeciesJob& job, const DiffusionTensorResult& r) {
  nlohmann::json shells = nlohmann::json::array();
  for (const auto& s : r.shells)
    shells.push_back({{"sigma_b", s.sigma_b}, {"beads", s.beads}, {"symmetry_order", s.symmetry_order},
                      {"largest_block", s.largest_block}, {"seconds", s.seconds},
                      {"D_trans", to_json(Vec3(s.diffusion.diagonal().head<3>()))},
                      {"D_rot", to_json(Vec3(s.diffusion.diagonal().tail<3>()))},
                      {"centre_of_diffusion", to_json(s.centre_of_diffusion)}});
  const Vec6 err = r.relative_error;
  return {{"name", job.name},
          {"shape", job.shape_json},
          {"D_trans", to_json(r.D_trans())},
          {"D_rot", to_json(r.D_rot())},
          {"hydro",
           {{"method", method_of(job, r)},
            {"extrapolation", extrapolation_name(r.extrapolation)},
            {"extrapolation_rule", extrapolation_name(r.rule)},
            {"diffusion_tensor", to_json(r.diffusion)},
            {"resistance_tensor", to_json(r.resistance)},
            {"centre_of_diffusion", to_json(r.centre_of_diffusion)},
            {"max_relative_coupling", r.relative_coupling},
            {"extrapolation_error", {{"D_trans", to_json(Vec3(err.head<3>()))}, {"D_rot", to_json(Vec3(err.tail<3>()))},
                                     {"compared_with", r.error_reference_of(r.extrapolation)}}},
            {"shells", shells}}}};
}

void print_summary(const std::string& name, const DiffusionTensorResult& r) {
  std::printf("%-16s D_trans = %.5g %.5g %.5g   D_rot = %.5g %.5g %.5g   %s extrapolation%s, error ≤ %.2g%%   coupling %.1e\n",
              name.c_str(), r.D_trans().x(), r.D_trans().y(), r.D_trans().z(), r.D_rot().x(), r.D_rot().y(), r.D_rot().z(),
              extrapolation_name(r.extrapolation).c_str(), r.rule == ExtrapolationRule::Auto ? " (auto)" : "",
              100.0 * r.relative_error.maxCoeff(), r.relative_coupling);
  std::fflush(stdout);
}

tool::Description description() {
  tool::Description d;
  d.role = tool::Role::Tensors;
  d.replica = false;
  d.inputs = {"none", 0, 0, "none: the shapes come from the configuration"};
  d.output = {"species", "JSON, or HDF5 for a .h5 output",
              "a species file (D_trans, D_rot, tensors and the shell series per species) that config and dmc read through "
              "diffusion_from", nullptr};
  d.parameters = {
      tool::required("species", "array", "{name, shape, and optionally shells | bead_radii, construction, extrapolation}"),
      tool::optional("shells", "object", nlohmann::json{{"count", 5}, {"max_beads", 6000}, {"size_ratio", 2.0}},
                     "the shell series of every species that gives none: {count, max_beads, size_ratio}"),
      tool::optional("bead_radii", "array", nullptr, "explicit bead radii (>= 3 distinct) instead of shells"),
      tool::optional("symmetry", "boolean", true, "use the mirror-symmetry block split when the shell allows it"),
      tool::optional("construction", "string", "surface_grid", "surface_grid | cell_centres, for species that give none"),
      tool::optional("extrapolation", "string", "auto", "auto | linear | quadratic fit to zero bead size, for species that give none"),
  };
  d.cost = {{"kind", "not_estimated"},
            {"why", "seconds to minutes per species (docs/hydro.md gives timings); the runner's estimate leaves it out"}};
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const tool::ToolInfo info{"anisodyn-hydro", "infinite-dilution diffusion tensors of rigid particles from shell models",
                            "The output is a species file: JSON, or HDF5 when it ends in .h5. Units: lengths in the shape's "
                            "unit ℓ, D_trans in ℓ²/τ, D_rot in rad²/τ, with τ = ηℓ³/k_BT. See docs/hydro.md.",
                            description()};
  return tool::run_tool(argc, argv, info, [&](tool::CommonOptions& opt) {
    if (!opt.inputs.empty()) throw InputError("--input", "", "anisodyn-hydro takes no input file (shapes come from --config)");
    if (opt.output.empty()) throw InputError("--output", "", "expected an output species file (.json or .h5)");
    tool::check_output_writable(opt.output);
    tool::ConfigNode cfg(opt.config, opt.config_name());
    const HydroConfig config = parse_hydro_config(cfg);
    cfg.finish();
#ifdef _OPENMP
    omp_set_num_threads(std::max(1, opt.threads));
#endif
    ResistanceOptions options;
    options.use_symmetry = config.use_symmetry;

    nlohmann::json species = nlohmann::json::array();
    for (const auto& job : config.species) {
      const auto progress = [&](const ShellSolution& s, std::size_t k, std::size_t total) {
        if (opt.quiet) return;
        std::fprintf(stderr, "%s: shell %zu/%zu  σ_b = %.4g  %zu beads  (mirror group %d, largest block %zu)  %.2f s\n",
                     job.name.c_str(), k + 1, total, s.sigma_b, s.beads, s.symmetry_order, s.largest_block, s.seconds);
      };
      const DiffusionTensorResult r = compute_diffusion_tensor(job.shape, job.bead_radii, options, progress, job.construction,
                                                               job.extrapolation);
      if (!opt.quiet) print_summary(job.name, r);
      species.push_back(species_entry(job, r));
    }
    const nlohmann::json document{
        {"format", "anisodyn-species"},
        {"version", 1},
        {"units", {{"length", "the unit of the shape dimensions (T for boards, σ for cubes)"},
                   {"D_trans", "length²/τ along the body axes x, y, z (T, W, L for boards)"},
                   {"D_rot", "rad²/τ about the body axes x, y, z"},
                   {"tau", "η length³ / k_BT"}}},
        {"parameters", opt.config},
        {"provenance", tool::make_provenance(info.name, opt.argv, {})},
        {"species", species}};
    io::write_species_file(opt.output, document);
  });
}
