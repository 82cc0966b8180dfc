#pragma once
// Species files: infinite-dilution diffusion coefficients of rigid particles, written by
// anisodyn-hydro and read by anisodyn-config and anisodyn-dmc (docs/hydro.md).
//
// The document is JSON:
//   {"format": "anisodyn-species", "version": 1, "units": {...}, "provenance": {...},
//    "species": [{"name", "shape", "D_trans": [T, W, L], "D_rot": [T, W, L], "hydro": {...}}]}
// where D_trans/D_rot are along/about the body axes in the study's reduced units. A file ending in
// .h5/.hdf5 holds the same document as the string dataset /species_file plus, for h5py users, one
// group /species/<name> with numeric datasets (D_trans, D_rot, diffusion_tensor, …).
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/core/types.hpp"

namespace anisodyn::io {

bool is_hdf5_path(const std::string& path);

/// Writes atomically (.partial + rename), as JSON or HDF5 by the file extension.
void write_species_file(const std::string& path, const nlohmann::json& document);

/// Reads either form; InputError(path, …) when missing, unreadable or not a species file.
nlohmann::json read_species_file(const std::string& path);

/// The entry named `name`; InputError(path, "species", "…known names…") when absent.
const nlohmann::json& species_file_entry(const nlohmann::json& document, const std::string& path, const std::string& name);

}  // namespace anisodyn::io
