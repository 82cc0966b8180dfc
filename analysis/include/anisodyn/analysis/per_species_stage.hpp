#pragma once
// The per-species stage: most stages analyse each selected species on its own, one analysis object
// per species, all fed each replica as it is loaded (one pass over the files whatever the number of
// species), then written species by species. run_per_species is that loop, once, so a stage's
// main() says only what to build for a species and what to write from it.
//
// Analysis: accumulate(const Trajectory&, int species_index) per replica; whatever else finish()
// calls (compute(), a second pass of its own through run.each_replica, ...).
#include <cstddef>
#include <type_traits>
#include <vector>

#include "anisodyn/analysis/species_selection.hpp"
#include "anisodyn/analysis/stage.hpp"

namespace anisodyn::analysis {

/// The species of `request` (the config key "species"), one make() each, every replica loaded with
/// `needs` and given to each analysis, then finish(species, analysis, time grid) species by species
/// in the file's order. The time grid is each_replica's (the mean time stamp of each frame over the
/// replicas).
template <class Make, class Finish>
void run_per_species(const StageRun& run, const SpeciesRequest& request, const TrajectoryNeeds& needs, Make&& make, Finish&& finish) {
  using Analysis = std::invoke_result_t<Make&>;
  const std::vector<SelectedSpecies> species = select_species(run.inputs.front(), request, run.opt.config_name(), "species");
  std::vector<Analysis> analyses;
  analyses.reserve(species.size());
  for (std::size_t k = 0; k < species.size(); ++k) analyses.push_back(make());
  const std::vector<double> grid = run.each_replica(needs, [&](const Trajectory& t, std::size_t) {
    for (std::size_t k = 0; k < species.size(); ++k) analyses[k].accumulate(t, species[k].index);
  });
  for (std::size_t k = 0; k < species.size(); ++k) finish(species[k], analyses[k], grid);
}

}  // namespace anisodyn::analysis
