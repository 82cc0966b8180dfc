#include "anisodyn/io/species_file.hpp"

#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/io/hdf5_support.hpp"

namespace anisodyn::io {

namespace {

constexpr const char* kDocumentDataset = "/species_file";

void require(bool ok, const std::string& path, const std::string& what) {
  if (!ok) throw RuntimeFailure(path + ": HDF5 error while " + what);
}

std::vector<double> flat(const nlohmann::json& j) {
  std::vector<double> out;
  if (j.is_array()) for (const auto& x : j) { auto v = flat(x); out.insert(out.end(), v.begin(), v.end()); }
  else if (j.is_number()) out.push_back(j.get<double>());
  return out;
}

/// Numeric mirror of one species entry for h5py users; the JSON document stays authoritative.
void write_species_group(hid_t species_root, const nlohmann::json& s, const std::string& path) {
  const detail::WriteContext w(path);
  detail::Handle g = w.group(species_root, s.at("name").get<std::string>());
  w.double_dataset(g.get(), "D_trans", {3}, flat(s.at("D_trans")));
  w.double_dataset(g.get(), "D_rot", {3}, flat(s.at("D_rot")));
  if (!s.contains("hydro")) return;
  const auto& h = s.at("hydro");
  w.double_dataset(g.get(), "diffusion_tensor", {6, 6}, flat(h.at("diffusion_tensor")));
  w.double_dataset(g.get(), "centre_of_diffusion", {3}, flat(h.at("centre_of_diffusion")));
  const auto& shells = h.at("shells");
  std::vector<double> sigma, beads, dt, dr;
  for (const auto& sh : shells) {
    sigma.push_back(sh.at("sigma_b").get<double>());
    beads.push_back(sh.at("beads").get<double>());
    for (double x : flat(sh.at("D_trans"))) dt.push_back(x);
    for (double x : flat(sh.at("D_rot"))) dr.push_back(x);
  }
  const auto n = static_cast<hsize_t>(shells.size());
  w.double_dataset(g.get(), "shell_sigma_b", {n}, sigma);
  w.double_dataset(g.get(), "shell_beads", {n}, beads);
  w.double_dataset(g.get(), "shell_D_trans", {n, 3}, dt);
  w.double_dataset(g.get(), "shell_D_rot", {n, 3}, dr);
}

void write_hdf5(const std::string& file, const nlohmann::json& doc) {
  detail::Handle f(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  require(f.get() >= 0, file, "creating the file");
  const std::string text = doc.dump(1);
  detail::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.size());
  detail::Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  detail::Handle ds(H5Dcreate2(f.get(), kDocumentDataset, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  require(ds.get() >= 0 && H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) >= 0, file, "writing the document");
  detail::Handle root(H5Gcreate2(f.get(), "/species", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  for (const auto& s : doc.at("species")) write_species_group(root.get(), s, file);
}

std::string read_hdf5_document(const std::string& path) {
  const detail::QuietHdf5 quiet;
  detail::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (f.get() < 0) throw InputError(path, "", "cannot open as HDF5");
  detail::Handle ds(H5Dopen2(f.get(), kDocumentDataset, H5P_DEFAULT), H5Dclose);
  if (ds.get() < 0) throw InputError(path, "", std::string("not a species file: no dataset ") + kDocumentDataset);
  detail::Handle type(H5Dget_type(ds.get()), H5Tclose);
  std::string text(H5Tget_size(type.get()), '\0');
  detail::Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem.get(), text.size());
  require(H5Dread(ds.get(), mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) >= 0, path, "reading the document");
  return text;
}

}  // namespace

bool is_hdf5_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".h5" || ext == ".hdf5";
}

void write_species_file(const std::string& path, const nlohmann::json& document) {
  tool::AtomicOutput out(path);
  if (is_hdf5_path(path)) {
    write_hdf5(out.partial_path(), document);
  } else {
    std::ofstream f(out.partial_path());
    f << document.dump(1) << "\n";
    if (!f) throw RuntimeFailure(path + ": cannot write the species file");
  }
  out.commit();
}

nlohmann::json read_species_file(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "", "cannot open file: no such species file");
  nlohmann::json doc = is_hdf5_path(path) ? tool::parse_json_text(read_hdf5_document(path), path) : tool::load_json_file(path);
  if (!doc.is_object() || doc.value("format", "") != "anisodyn-species" || !doc.contains("species") || !doc["species"].is_array())
    throw InputError(path, "format", "expected an anisodyn species file (\"format\": \"anisodyn-species\", written by anisodyn-hydro)");
  return doc;
}

const nlohmann::json& species_file_entry(const nlohmann::json& document, const std::string& path, const std::string& name) {
  std::string known;
  for (const auto& s : document.at("species")) {
    if (s.value("name", "") == name) return s;
    known += (known.empty() ? "" : ", ") + s.value("name", "?");
  }
  throw InputError(path, "species", "no species named '" + name + "' (the file has: " + known + ")");
}

}  // namespace anisodyn::io
