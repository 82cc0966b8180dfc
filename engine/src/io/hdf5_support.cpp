// HDF5 plumbing shared by the io module's files and the analysis library (hdf5_support.hpp).
#include "anisodyn/io/hdf5_support.hpp"

#include <cstring>

namespace anisodyn::io::detail {

/// The current HDF5 error stack as one line (API-level description and the innermost cause).
std::string hdf5_error_text() {
  struct Acc { std::string api, inner; } acc;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
        auto* a = static_cast<Acc*>(data);
        const std::string d = e->desc ? e->desc : "";
        if (n == 0) a->api = d;
        a->inner = d;
        return 0;
      },
      &acc);
  H5Eclear2(H5E_DEFAULT);
  if (acc.api.empty() && acc.inner.empty()) return "unknown HDF5 error";
  if (acc.inner.empty() || acc.inner == acc.api) return acc.api;
  return acc.api + " (" + acc.inner + ")";
}

Handle vlen_string_type() {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return Handle(t, H5Tclose);
}

std::string dims_text(const std::vector<hsize_t>& d) {
  std::string s = "[";
  for (std::size_t k = 0; k < d.size(); ++k) s += (k ? ", " : "") + std::to_string(d[k]);
  return s + "]";
}

std::vector<hsize_t> dataset_dims(hid_t ds) {
  Handle space(H5Dget_space(ds), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> d(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
  return d;
}

hsize_t product(const std::vector<hsize_t>& d) {
  hsize_t p = 1;
  for (auto x : d) p *= x;
  return p;
}

std::string read_string_from(hid_t obj, bool attribute, const std::string& file, const std::string& where) {
  Handle type(attribute ? H5Aget_type(obj) : H5Dget_type(obj), H5Tclose);
  Handle space(attribute ? H5Aget_space(obj) : H5Dget_space(obj), H5Sclose);
  if (!type.valid() || !space.valid() || H5Tget_class(type.get()) != H5T_STRING)
    throw InputError(file, where, "expected a string");
  if (H5Sget_simple_extent_npoints(space.get()) != 1) throw InputError(file, where, "expected a single string");
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle mem = vlen_string_type();
    char* p = nullptr;
    const herr_t rc = attribute ? H5Aread(obj, mem.get(), &p) : H5Dread(obj, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &p);
    if (rc < 0) throw InputError(file, where, "cannot read string: " + hdf5_error_text());
    std::string out = p ? p : "";
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(mem.get(), space.get(), H5P_DEFAULT, &p);
#else
    H5Dvlen_reclaim(mem.get(), space.get(), H5P_DEFAULT, &p);
#endif
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem.get(), size);
  std::string buf(size, '\0');
  const herr_t rc = attribute ? H5Aread(obj, mem.get(), buf.data())
                              : H5Dread(obj, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
  if (rc < 0) throw InputError(file, where, "cannot read string: " + hdf5_error_text());
  buf.resize(std::strlen(buf.c_str()));
  return buf;
}

std::vector<std::string> read_string_array(hid_t ds, const std::string& file, const std::string& where) {
  Handle type(H5Dget_type(ds), H5Tclose);
  Handle space(H5Dget_space(ds), H5Sclose);
  if (H5Tget_class(type.get()) != H5T_STRING) throw InputError(file, where, "expected an array of strings");
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get()));
  std::vector<std::string> out;
  if (n == 0) return out;
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle mem = vlen_string_type();
    std::vector<char*> ptrs(n, nullptr);
    if (H5Dread(ds, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
      throw InputError(file, where, "cannot read strings: " + hdf5_error_text());
    for (char* p : ptrs) out.emplace_back(p ? p : "");
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(mem.get(), space.get(), H5P_DEFAULT, ptrs.data());
#else
    H5Dvlen_reclaim(mem.get(), space.get(), H5P_DEFAULT, ptrs.data());
#endif
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mem.get(), size);
  std::vector<char> buf(n * size);
  if (H5Dread(ds, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    throw InputError(file, where, "cannot read strings: " + hdf5_error_text());
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = buf.data() + i * size;
    out.emplace_back(p, strnlen(p, size));
  }
  return out;
}

}  // namespace anisodyn::io::detail
