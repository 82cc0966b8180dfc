#include "anisodyn/analysis/analysis_output.hpp"

#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/io/hdf5_support.hpp"
#include "anisodyn/version.hpp"

namespace anisodyn::analysis {

using io::detail::Handle;
using io::detail::QuietHdf5;
using io::detail::WriteContext;

Table& Table::add(std::string column, std::string units, std::string def, std::vector<double> values) {
  if (!columns.empty() && values.size() != rows())
    throw RuntimeFailure("table '" + name + "': column '" + column + "' has " + std::to_string(values.size()) +
                         " rows, the table " + std::to_string(rows()));
  columns.push_back({std::move(column), std::move(units), std::move(def), std::move(values)});
  return *this;
}

AnalysisOutput::AnalysisOutput(std::string path, nlohmann::json parameters, nlohmann::json provenance)
    : path_(std::move(path)), parameters_(std::move(parameters)), provenance_(std::move(provenance)) {}

Table& AnalysisOutput::table(const std::string& name, const std::string& definition) {
  for (auto& t : tables_)
    if (t.name == name) return t;
  tables_.push_back({name, definition, {}});
  return tables_.back();
}

void AnalysisOutput::scalar(Scalar s) { scalars_.push_back(std::move(s)); }

std::string AnalysisOutput::csv_path(const std::string& table) const {
  std::string stem = path_;
  for (const char* ext : {".h5", ".hdf5"}) {
    const std::string e = ext;
    if (stem.size() > e.size() && stem.compare(stem.size() - e.size(), e.size(), e) == 0) {
      stem.resize(stem.size() - e.size());
      break;
    }
  }
  return stem + "." + table + ".csv";
}

namespace {

std::string csv_number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

void write_table_csv(const Table& t, const std::string& path, const nlohmann::json& window) {
  std::ofstream f(path);
  if (!f) throw RuntimeFailure("cannot write " + path);
  if (!window.is_null()) f << "# window: " << window.dump() << "\n";
  f << "# " << t.definition << "\n";
  for (const auto& c : t.columns) f << "# " << c.name << " [" << c.units << "]: " << c.definition << "\n";
  for (std::size_t k = 0; k < t.columns.size(); ++k) f << (k ? "," : "") << csv_field(t.columns[k].name);
  f << "\n";
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t k = 0; k < t.columns.size(); ++k) f << (k ? "," : "") << csv_number(t.columns[k].values[r]);
    f << "\n";
  }
  f.close();
  if (!f) throw RuntimeFailure("cannot write " + path);
}

void write_scalars_csv(const std::vector<Scalar>& scalars, const std::string& path) {
  std::ofstream f(path);
  if (!f) throw RuntimeFailure("cannot write " + path);
  f << "name,value,standard_error,units,definition,details\n";
  for (const auto& s : scalars)
    f << csv_field(s.name) << "," << csv_number(s.value) << "," << csv_number(s.error) << "," << csv_field(s.units) << ","
      << csv_field(s.definition) << "," << csv_field(s.details.dump()) << "\n";
  f.close();
  if (!f) throw RuntimeFailure("cannot write " + path);
}

}  // namespace

void AnalysisOutput::write(bool csv) const {
  std::vector<Table> tables = tables_;
  for (auto& t : tables)
    for (auto& c : t.columns) c.units = units_.express(c.units);
  std::vector<Scalar> scalars = scalars_;
  for (auto& s : scalars) s.units = units_.express(s.units);
  QuietHdf5 quiet;
  std::vector<tool::AtomicOutput> outputs;
  outputs.emplace_back(path_);
  {
    Handle file(H5Fcreate(outputs.back().partial_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    if (!file.valid()) throw RuntimeFailure("cannot create " + outputs.back().partial_path());
    const hid_t f = file.get();
    const WriteContext w(outputs.back().partial_path());
    w.string_attribute(f, "tool", provenance_.value("tool", std::string()));
    w.string_attribute(f, "tool_version", std::string(kVersion) + " (" + kGitRevision + ")");
    w.string_attribute(f, "git_revision", kGitRevision);
    w.string_attribute(f, "created_utc", provenance_.value("created_utc", std::string()));
    w.string_attribute(f, "inputs", provenance_.value("inputs", nlohmann::json::array()).dump());
    if (!window_.is_null()) w.string_attribute(f, "window", window_.dump());
    w.string_dataset(f, "parameters", parameters_.dump(2));
    w.string_dataset(f, "provenance", provenance_.dump(2));
    std::set<std::string> names;
    for (const auto& t : tables) {
      if (!names.insert(t.name).second || t.name == "scalars") throw RuntimeFailure("duplicate table name " + t.name);
      Handle g = w.group(f, t.name);
      w.string_attribute(g.get(), "definition", t.definition);
      for (const auto& c : t.columns) {
        Handle ds = w.double_dataset(g.get(), c.name, c.values);
        w.string_attribute(ds.get(), "units", c.units);
        w.string_attribute(ds.get(), "definition", c.definition);
      }
    }
    if (!scalars.empty()) {
      Handle g = w.group(f, "scalars");
      w.string_attribute(g.get(), "definition", "scalar results: value and standard error");
      for (const auto& s : scalars) {
        Handle ds = w.double_dataset(g.get(), s.name, {s.value, s.error});
        w.string_attribute(ds.get(), "units", s.units);
        w.string_attribute(ds.get(), "definition", s.definition);
        w.string_attribute(ds.get(), "details", s.details.dump());
      }
    }
    if (!file.close()) throw RuntimeFailure("cannot close " + outputs.back().partial_path());
  }
  if (csv) {
    for (const auto& t : tables) {
      outputs.emplace_back(csv_path(t.name));
      write_table_csv(t, outputs.back().partial_path(), window_);
    }
    if (!scalars.empty()) {
      outputs.emplace_back(csv_path("scalars"));
      write_scalars_csv(scalars, outputs.back().partial_path());
    }
  }
  for (auto& o : outputs) o.commit();
}

}  // namespace anisodyn::analysis
