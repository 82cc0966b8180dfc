#pragma once
// HDF5 plumbing shared by every HDF5 file anisodyn writes or reads (H5MD trajectories and
// checkpoints, analysis outputs, species files): owning handles, quiet error stacks, dataset and
// attribute writers that throw RuntimeFailure naming the file, and readers that throw InputError
// naming the file and the HDF5 path.
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::io::detail {

/// Owning hid_t with the matching close function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) { reset(); id_ = o.id_; closer_ = o.closer_; o.id_ = H5I_INVALID_HID; }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }
  void reset() {
    if (id_ >= 0 && closer_) closer_(id_);
    id_ = H5I_INVALID_HID;
  }
  /// Closes and reports whether closing succeeded.
  bool close() {
    const bool ok = id_ < 0 || !closer_ || closer_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// Silences HDF5's automatic error-stack printing for the lifetime of the object; errors are
/// reported through exceptions instead.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// The current HDF5 error stack as one line (API-level description and the innermost cause).
std::string hdf5_error_text();
/// Variable-length UTF-8 string type.
Handle vlen_string_type();
/// "[a, b, …]" for error messages.
std::string dims_text(const std::vector<hsize_t>& d);
std::vector<hsize_t> dataset_dims(hid_t ds);
hsize_t product(const std::vector<hsize_t>& d);

// ---- writing helpers (throw RuntimeFailure) ----------------------------------------------------------

/// Writers of groups, datasets and attributes into one file; every failure is a RuntimeFailure
/// naming the file, what was being written and the HDF5 error.
class WriteContext {
 public:
  explicit WriteContext(std::string file) : file_(std::move(file)) {}

  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void check_rc(herr_t rc, const std::string& what) const {
    if (rc < 0) fail(what);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw RuntimeFailure("HDF5 error writing '" + file_ + "': " + what + ": " + hdf5_error_text());
  }

  Handle group(hid_t loc, const std::string& name) const {
    return Handle(check(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create group " + name),
                  H5Gclose);
  }

  void string_attribute(hid_t obj, const std::string& name, const std::string& value) const {
    if (H5Aexists(obj, name.c_str()) > 0) check_rc(H5Adelete(obj, name.c_str()), "replace attribute " + name);
    Handle type = vlen_string_type();
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
                H5Aclose);
    const char* p = value.c_str();
    check_rc(H5Awrite(attr.get(), type.get(), &p), "write attribute " + name);
  }

  void string_array_attribute(hid_t obj, const std::string& name, const std::vector<std::string>& values) const {
    Handle type = vlen_string_type();
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
                H5Aclose);
    std::vector<const char*> ptrs;
    for (const auto& v : values) ptrs.push_back(v.c_str());
    check_rc(H5Awrite(attr.get(), type.get(), ptrs.data()), "write attribute " + name);
  }

  void int_attribute(hid_t obj, const std::string& name, const std::vector<std::int32_t>& values, bool scalar) const {
    const hsize_t n = values.size();
    Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name.c_str(), H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name),
                H5Aclose);
    check_rc(H5Awrite(attr.get(), H5T_NATIVE_INT32, values.data()), "write attribute " + name);
  }

  Handle string_dataset(hid_t loc, const std::string& name, const std::string& value) const {
    Handle type = vlen_string_type();
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    Handle ds(check(H5Dcreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "create dataset " + name),
              H5Dclose);
    write_string(ds.get(), value, name);
    return ds;
  }

  void write_string(hid_t ds, const std::string& value, const std::string& name) const {
    Handle type = vlen_string_type();
    const char* p = value.c_str();
    check_rc(H5Dwrite(ds, type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &p), "write dataset " + name);
  }

  void string_array_dataset(hid_t loc, const std::string& name, const std::vector<std::string>& values) const {
    Handle type = vlen_string_type();
    const hsize_t n = values.size();
    Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    Handle ds(check(H5Dcreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "create dataset " + name),
              H5Dclose);
    std::vector<const char*> ptrs;
    for (const auto& v : values) ptrs.push_back(v.c_str());
    if (n > 0) check_rc(H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), "write dataset " + name);
  }

  Handle double_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                        const std::vector<double>& values) const {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    Handle ds(check(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "create dataset " + name),
              H5Dclose);
    if (!values.empty())
      check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write dataset " + name);
    return ds;
  }
  /// One-dimensional float64 dataset.
  Handle double_dataset(hid_t loc, const std::string& name, const std::vector<double>& values) const {
    return double_dataset(loc, name, {static_cast<hsize_t>(values.size())}, values);
  }

  /// Dataset of shape [0, row_dims…] extendable along the first axis, chunked by `chunk_rows`.
  Handle extendable(hid_t loc, const std::string& name, hid_t file_type, const std::vector<hsize_t>& row_dims,
                    hsize_t chunk_rows) const {
    std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{std::max<hsize_t>(chunk_rows, 1)};
    for (hsize_t d : row_dims) {
      dims.push_back(d);
      maxdims.push_back(d > 0 ? d : H5S_UNLIMITED);  // HDF5 wants chunk ≤ fixed maximum sizes
      chunk.push_back(std::max<hsize_t>(d, 1));
    }
    Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()), "dataspace " + name),
                 H5Sclose);
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    check_rc(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "chunking " + name);
    return Handle(check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                        "create dataset " + name),
                  H5Dclose);
  }

  /// Appends `rows` rows (each of shape row_dims) at row index `offset`.
  void append(hid_t ds, const std::vector<hsize_t>& row_dims, hsize_t offset, hsize_t rows, hid_t mem_type,
              const void* data, const std::string& name) const {
    std::vector<hsize_t> newdims{offset + rows}, start{offset}, count{rows};
    for (hsize_t d : row_dims) { newdims.push_back(d); start.push_back(0); count.push_back(d); }
    check_rc(H5Dset_extent(ds, newdims.data()), "extend dataset " + name);
    if (product(count) == 0) return;
    Handle fspace(check(H5Dget_space(ds), "dataspace of " + name), H5Sclose);
    check_rc(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "select rows of " + name);
    Handle mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
    check_rc(H5Dwrite(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, data), "write dataset " + name);
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

/// One string, from a dataset or an attribute (fixed or variable length).
std::string read_string_from(hid_t obj, bool attribute, const std::string& file, const std::string& where);
/// A one-dimensional string dataset (fixed or variable length).
std::vector<std::string> read_string_array(hid_t ds, const std::string& file, const std::string& where);

/// Read access to an open HDF5 file; every problem is an InputError naming the HDF5 path.
struct FileReader {
  std::string path;
  hid_t fid = H5I_INVALID_HID;

  [[noreturn]] void bad(const std::string& where, const std::string& problem) const {
    throw InputError(path, where, problem);
  }

  bool exists(const std::string& hpath) const {
    std::size_t pos = 1;
    while (pos <= hpath.size()) {
      std::size_t next = hpath.find('/', pos);
      if (next == std::string::npos) next = hpath.size();
      const std::string prefix = hpath.substr(0, next);
      if (H5Lexists(fid, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      pos = next + 1;
    }
    return H5Oexists_by_name(fid, hpath.c_str(), H5P_DEFAULT) > 0;
  }

  Handle open(const std::string& hpath, H5I_type_t type) const {
    const char* what = type == H5I_GROUP ? "group" : "dataset";
    if (!exists(hpath)) bad(hpath, std::string("missing required ") + what);
    hid_t id = H5Oopen(fid, hpath.c_str(), H5P_DEFAULT);
    if (id < 0) bad(hpath, std::string("cannot open: ") + hdf5_error_text());
    if (H5Iget_type(id) != type) {
      H5Oclose(id);
      bad(hpath, std::string("expected a ") + what);
    }
    return Handle(id, type == H5I_GROUP ? H5Gclose : H5Dclose);
  }
  Handle dataset(const std::string& hpath) const { return open(hpath, H5I_DATASET); }
  Handle group(const std::string& hpath) const { return open(hpath, H5I_GROUP); }

  void read_all(hid_t ds, hid_t mem_type, void* out, const std::string& hpath) const {
    if (H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      bad(hpath, "cannot read: " + hdf5_error_text());
  }

  void read_block(hid_t ds, const std::vector<hsize_t>& start, const std::vector<hsize_t>& count, hid_t mem_type,
                  void* out, const std::string& hpath) const {
    if (product(count) == 0) return;
    Handle fspace(H5Dget_space(ds), H5Sclose);
    Handle mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
    if (H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0 ||
        H5Dread(ds, mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, out) < 0)
      bad(hpath, "cannot read: " + hdf5_error_text());
  }

  std::vector<hsize_t> dims(const std::string& hpath) const {
    Handle ds = dataset(hpath);
    return dataset_dims(ds.get());
  }

  /// Rows first, first + frame_stride, … (frame_count of them) of a dataset whose first axis counts frames (one
  /// strided hyperslab); the other axes are read whole. The caller has checked the shape.
  template <class T>
  std::vector<T> read_frame_rows(const std::string& hpath, hid_t mem_type, std::size_t first, std::size_t frame_count,
                                 std::size_t frame_stride) const {
    Handle ds = dataset(hpath);
    std::vector<hsize_t> count = dataset_dims(ds.get());
    std::vector<hsize_t> start(count.size(), 0), stride(count.size(), 1);
    start[0] = first;
    stride[0] = std::max<std::size_t>(frame_stride, 1);
    count[0] = frame_count;
    std::vector<T> out(product(count));
    if (out.empty()) return out;
    Handle fspace(H5Dget_space(ds.get()), H5Sclose);
    Handle mspace(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
    if (H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), stride.data(), count.data(), nullptr) < 0 ||
        H5Dread(ds.get(), mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, out.data()) < 0)
      bad(hpath, "cannot read: " + hdf5_error_text());
    return out;
  }

  template <class T>
  std::vector<T> read_vector(const std::string& hpath, hid_t mem_type, std::vector<hsize_t>* dims_out = nullptr) const {
    Handle ds = dataset(hpath);
    const auto d = dataset_dims(ds.get());
    std::vector<T> out(product(d));
    if (!out.empty()) read_all(ds.get(), mem_type, out.data(), hpath);
    if (dims_out) *dims_out = d;
    return out;
  }

  std::string read_text(const std::string& hpath) const {
    Handle ds = dataset(hpath);
    return read_string_from(ds.get(), false, path, hpath);
  }

  nlohmann::json read_json(const std::string& hpath) const {
    const std::string text = read_text(hpath);
    try {
      return tool::parse_json_text(text, path);
    } catch (const InputError& e) {
      // Re-anchor the parser's message at the dataset holding the text.
      const std::string msg = e.what();
      const auto p = msg.find("invalid JSON");
      bad(hpath, p == std::string::npos ? msg : msg.substr(p));
    }
  }

};

}  // namespace anisodyn::io::detail
