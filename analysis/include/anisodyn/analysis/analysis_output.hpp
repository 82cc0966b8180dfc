#pragma once
// The output of an analysis stage (architecture §4): one HDF5 file with named tables and scalar
// results, every dataset with `units` and a one-line `definition`, plus the inputs (paths and
// SHA-256), tool_version, the parameters and provenance; and optionally one CSV file per table
// (<output stem>.<table>.csv) and one for the scalars. All files are written atomically.
//
// HDF5 layout:
//   /                      attrs tool, tool_version, git_revision, created_utc, inputs (JSON text),
//                          window (JSON text; only when the stage was given a time window)
//   /parameters            JSON text of the stage parameters
//   /provenance            JSON text (tool/provenance.hpp)
//   /<table>               group, attr definition
//   /<table>/<column>      float64 [rows], attrs units, definition
//   /scalars/<name>        float64 [2] = (value, standard error), attrs units, definition, details (JSON)
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/tool/unit_system.hpp"

namespace anisodyn::analysis {

/// A table column from each row of a per-replica (or per-item) result: `get` is a data member
/// pointer or any callable on a row.
template <class Rows, class Get>
std::vector<double> column_of(const Rows& rows, Get get) {
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back(static_cast<double>(std::invoke(get, row)));
  return out;
}

/// 0, 1, …, n − 1: the index column of a table with one row per input.
inline std::vector<double> index_column(std::size_t n) {
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = static_cast<double>(k);
  return out;
}

struct Column {
  std::string name, units, definition;
  std::vector<double> values;
};

struct Table {
  std::string name, definition;
  std::vector<Column> columns;
  Table& add(std::string column, std::string units, std::string definition, std::vector<double> values);
  std::size_t rows() const { return columns.empty() ? 0 : columns.front().values.size(); }
};

struct Scalar {
  std::string name;
  double value = 0.0, error = 0.0;
  std::string units, definition;
  nlohmann::json details = nlohmann::json::object();  // fit window, method, counts …
};

class AnalysisOutput {
 public:
  AnalysisOutput(std::string path, nlohmann::json parameters, nlohmann::json provenance);

  Table& table(const std::string& name, const std::string& definition);
  void scalar(Scalar s);
  /// Provenance is made last (it hashes the inputs), just before write().
  void set_provenance(nlohmann::json provenance) { provenance_ = std::move(provenance); }
  /// The time window the stage analysed (frame_window.hpp record), written as the root attribute
  /// `window` and as a comment line heading each CSV table.
  void set_window(nlohmann::json record) { window_ = std::move(record); }
  /// The unit system of the analysed runs: units are given symbolically (tau, length, sigma) and
  /// written in this system (tool/unit_system.hpp). Reduced unless set.
  void set_unit_system(tool::UnitSystem units) { units_ = units; }
  const std::vector<Table>& tables() const { return tables_; }
  const std::vector<Scalar>& scalars() const { return scalars_; }

  /// Writes the HDF5 file (and CSV files when `csv`); all-or-nothing.
  void write(bool csv) const;
  /// The CSV path of a table: <path without .h5>.<table>.csv
  std::string csv_path(const std::string& table) const;

 private:
  std::string path_;
  nlohmann::json parameters_, provenance_, window_;
  std::vector<Table> tables_;
  std::vector<Scalar> scalars_;
  tool::UnitSystem units_;
};

}  // namespace anisodyn::analysis
