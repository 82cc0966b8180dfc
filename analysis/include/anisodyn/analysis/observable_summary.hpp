#pragma once
// Means and drifts of an engine's observation rows (e.g. anisodyn-dpd's kinetic_temperature,
// pressure, total_energy; spec 60 C0): for each named observable, each component's mean over the
// rows inside the window, and for each drift observable the least-squares slope of its value against
// time. Samples are the replicas (a mean's error is then the jackknife over them, the standard error of
// the mean of replica means weighted by their rows); a single replica's rows are cut into `blocks`
// contiguous blocks, the jackknife over which respects the rows' correlation up to a block's length.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "anisodyn/analysis/replica_statistics.hpp"

namespace anisodyn::analysis {

struct ObservableRows {
  std::vector<double> time, value;  // value: rows × width
  std::size_t width = 1;
  std::string units;                // the observable's "units" attribute (empty if none)
};

/// The rows of `name` in `path` whose times pass keep(); InputError naming the file when it has no
/// such observable or no row in the window.
ObservableRows read_rows(const std::string& path, const std::string& name, const std::function<bool(double)>& keep);


/// Per component: the mean over all rows of all runs, with the error over the samples.
std::vector<Estimate> observable_means(const std::vector<ObservableRows>& runs, std::size_t blocks);
/// Per component: the slope of value against time: for one run, one line through its rows with the
/// jackknife error over its blocks; for several, one line per run, the mean slope and its standard error.
std::vector<Estimate> observable_drifts(const std::vector<ObservableRows>& runs, std::size_t blocks);

}  // namespace anisodyn::analysis
