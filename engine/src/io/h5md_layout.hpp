#pragma once
// What the H5MD writer and reader share beyond generic HDF5 plumbing: the species table's columns,
// chunking, names of per-particle elements and observables (layout: docs/file-format.md).
#include <set>
#include <string>
#include <vector>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/io/hdf5_support.hpp"

namespace anisodyn::io::h5md_layout {

using detail::FileReader;

ShapeKind shape_kind_from_name(const std::string& name, bool& ok);

inline constexpr hsize_t kScalarChunkRows = 4096;
inline constexpr hsize_t kObservableBufferRows = 4096;

/// Frames per chunk for per-particle data: chunks of about 128 KiB (well below the 1 MiB default
/// chunk cache, so partially filled chunks stay cached between frames, and small files stay small),
/// at most 64 frames; one frame per chunk for large systems. `hint` > 0 overrides.
hsize_t frames_per_chunk(std::size_t n, std::size_t width, std::size_t elem_size, std::size_t hint);
/// A name usable as one HDF5 link name.
bool valid_name(const std::string& name);
SpeciesTable read_species_table(const FileReader& m);
/// Number of leading entries of a non-decreasing step series that are ≤ last_step.
hsize_t rows_up_to(const std::vector<std::int64_t>& steps, std::int64_t last_step);
/// Adds the names of the links in an HDF5 group to `names`.
void insert_link_names(hid_t group, std::set<std::string>& names);
/// Groups of /particles/all other than the standard H5MD elements that hold a `value` dataset.
std::vector<std::string> extra_element_names(const FileReader& r);
/// Where observable `name` is stored (/observables/ or /anisodyn/observables/), or "" if nowhere.
std::string observable_path(const FileReader& r, const std::string& name);

}  // namespace anisodyn::io::h5md_layout
