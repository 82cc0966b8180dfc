// H5MD 1.1 writer and reader on the HDF5 C API. See include/anisodyn/io/h5md.hpp and
// docs/file-format.md for the layout; the comments here explain only implementation choices.
#include "anisodyn/io/h5md.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/version.hpp"
#include "anisodyn/io/hdf5_support.hpp"

namespace anisodyn::io {
namespace {

using detail::Handle;
using detail::QuietHdf5;

using nlohmann::json;

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

// ---- writing helpers (throw RuntimeFailure) ----------------------------------------------------------

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

  void double_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                      const std::vector<double>& values) const {
    Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    Handle ds(check(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                    "create dataset " + name),
              H5Dclose);
    if (!values.empty())
      check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write dataset " + name);
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

// ---- reading helpers (throw InputError naming the HDF5 path) -----------------------------------------

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

ShapeKind shape_kind_from_name(const std::string& name, bool& ok) {
  ok = true;
  for (int k = 0; k < kShapeKindCount; ++k) {
    if (name == shape_kind_name(static_cast<ShapeKind>(k))) return static_cast<ShapeKind>(k);
  }
  ok = false;
  return ShapeKind::Sphere;
}

constexpr hsize_t kScalarChunkRows = 4096;
constexpr hsize_t kObservableBufferRows = 4096;

/// Frames per chunk for per-particle data: chunks of about 128 KiB (well below the 1 MiB default
/// chunk cache, so partially filled chunks stay cached between frames, and small files stay small),
/// at most 64 frames; one frame per chunk for large systems. `hint` > 0 overrides.
hsize_t frames_per_chunk(std::size_t n, std::size_t width, std::size_t elem_size, std::size_t hint) {
  if (hint > 0) return static_cast<hsize_t>(hint);
  const std::size_t bytes = std::max<std::size_t>(n, 1) * std::max<std::size_t>(width, 1) * elem_size;
  return static_cast<hsize_t>(std::clamp<std::size_t>((std::size_t{1} << 17) / bytes, 1, 64));
}

bool valid_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

}  // namespace

namespace {

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

  /// Rows frames.frame(0), frames.frame(1), … of a dataset whose first axis counts frames (one
  /// strided hyperslab); the other axes are read whole. The caller has checked the shape.
  template <class T>
  std::vector<T> read_frame_rows(const std::string& hpath, hid_t mem_type, const FrameSlice& frames) const {
    Handle ds = dataset(hpath);
    std::vector<hsize_t> count = dataset_dims(ds.get());
    std::vector<hsize_t> start(count.size(), 0), stride(count.size(), 1);
    start[0] = frames.first;
    stride[0] = std::max<std::size_t>(frames.stride, 1);
    count[0] = frames.count;
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

  json read_json(const std::string& hpath) const {
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

  std::string observable_path(const std::string& name) const {
    if (!valid_name(name)) return "";
    for (const std::string base : {"/observables/", "/anisodyn/observables/"}) {
      if (exists(base + name)) return base + name;
    }
    return "";
  }
};


SpeciesTable read_species_table(const FileReader& m) {
  const std::string base = "/parameters/species";
  m.group(base);
  std::vector<std::string> names, shapes;
  {
    Handle ds = m.dataset(base + "/name");
    names = read_string_array(ds.get(), m.path, base + "/name");
  }
  {
    Handle ds = m.dataset(base + "/shape");
    shapes = read_string_array(ds.get(), m.path, base + "/shape");
  }
  const std::size_t ns = names.size();
  auto column = [&](const std::string& name, std::size_t width) {
    std::vector<hsize_t> d;
    auto v = m.read_vector<double>(base + "/" + name, H5T_NATIVE_DOUBLE, &d);
    const bool ok = width == 1 ? (d.size() == 1 && d[0] == ns) : (d.size() == 2 && d[0] == ns && d[1] == width);
    if (!ok)
      m.bad(base + "/" + name, "expected shape [" + std::to_string(ns) + (width > 1 ? ", " + std::to_string(width) : "") +
                                   "] (one row per species), got " + dims_text(d));
    return v;
  };
  if (shapes.size() != ns)
    m.bad(base + "/shape", "expected " + std::to_string(ns) + " entries, got " + std::to_string(shapes.size()));
  const auto edges = column("edges", 3), diameter = column("diameter", 1), length = column("length", 1),
             mass = column("mass", 1), dt = column("D_trans", 3), dr = column("D_rot", 3);
  SpeciesTable table(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    Species& s = table[i];
    s.name = names[i];
    bool ok = false;
    s.shape.kind = shape_kind_from_name(shapes[i], ok);
    if (!ok)
      m.bad(base + "/shape", "unknown shape '" + shapes[i] + "' for species " + std::to_string(i) +
                                 " (expected sphere, cuboid or spherocylinder)");
    s.shape.edges = Vec3(edges[3 * i], edges[3 * i + 1], edges[3 * i + 2]);
    s.shape.diameter = diameter[i];
    s.shape.length = length[i];
    s.mass = mass[i];
    s.D_trans = Vec3(dt[3 * i], dt[3 * i + 1], dt[3 * i + 2]);
    s.D_rot = Vec3(dr[3 * i], dr[3 * i + 1], dr[3 * i + 2]);
  }
  return table;
}

}  // namespace

// =====================================================================================================
// Writer
// =====================================================================================================

struct H5mdWriter::Impl {
  // Declared first, destroyed last: removes the partial file after all HDF5 handles are closed.
  tool::AtomicOutput out;
  WriteContext w;
  std::string path;

  Handle file, h5md, particles, all, box, parameters;
  Handle observables_group, anisodyn_group, checkpoint_group, engine_state;

  SpeciesTable species;
  bool species_written = false;
  std::size_t chunk_hint = 0;  // H5mdHeader::frames_per_chunk

  // Frames
  bool frames_initialized = false;
  std::size_t n = 0, frames = 0;
  std::int64_t last_step = 0;
  Handle step_ds, time_ds;
  Handle edges_value, position_value, image_value, orientation_value, species_value, id_value;
  struct Extra { Handle value; std::size_t width = 1; };
  std::map<std::string, Extra> extra;  // engine-specific per-particle elements

  struct Observable {
    Handle group, step, time, value;
    bool has_datasets = false;
    bool vector = false;
    std::size_t width = 1;
    std::size_t rows = 0;  // rows in the file
    std::vector<std::int64_t> bstep;
    std::vector<double> btime, bvalue;
  };
  std::map<std::string, Observable> observables;
  bool closed = false;  // committed or suspended

  Impl(const std::string& p) : out(p), w(p + ".partial"), path(p) {}

  void require_open() const {
    if (closed) throw RuntimeFailure("H5mdWriter: '" + path + "' was already committed or suspended");
  }

  void write_species_table(const SpeciesTable& table) {
    species = table;
    Handle g = w.group(parameters.get(), "species");
    const std::size_t ns = table.size();
    const hsize_t n_h = ns;
    std::vector<std::string> names, shapes;
    std::vector<double> edges, diameter, length, mass, dt, dr;
    for (const auto& s : table) {
      names.push_back(s.name);
      shapes.push_back(shape_kind_name(s.shape.kind));
      for (int k = 0; k < 3; ++k) {
        edges.push_back(s.shape.edges[k]);
        dt.push_back(s.D_trans[k]);
        dr.push_back(s.D_rot[k]);
      }
      diameter.push_back(s.shape.diameter);
      length.push_back(s.shape.length);
      mass.push_back(s.mass);
    }
    w.string_array_dataset(g.get(), "name", names);
    w.string_array_dataset(g.get(), "shape", shapes);
    w.double_dataset(g.get(), "edges", {n_h, 3}, edges);
    w.double_dataset(g.get(), "diameter", {n_h}, diameter);
    w.double_dataset(g.get(), "length", {n_h}, length);
    w.double_dataset(g.get(), "mass", {n_h}, mass);
    w.double_dataset(g.get(), "D_trans", {n_h, 3}, dt);
    w.double_dataset(g.get(), "D_rot", {n_h, 3}, dr);
    species_written = true;
  }

  /// A time-dependent element sharing the trajectory's step and time datasets (hard links).
  Handle element(hid_t parent, const std::string& name, hid_t file_type, const std::vector<hsize_t>& row_dims,
                 std::size_t elem_size) {
    Handle g = w.group(parent, name);
    w.check_rc(H5Lcreate_hard(all.get(), "position/step", g.get(), "step", H5P_DEFAULT, H5P_DEFAULT), "link step of " + name);
    w.check_rc(H5Lcreate_hard(all.get(), "position/time", g.get(), "time", H5P_DEFAULT, H5P_DEFAULT), "link time of " + name);
    std::size_t width = 1;
    for (std::size_t k = 1; k < row_dims.size(); ++k) width *= row_dims[k];
    return w.extendable(g.get(), "value", file_type, row_dims, frames_per_chunk(n, width, elem_size, chunk_hint));
  }

  void initialize_frames(std::size_t count) {
    n = count;
    const hsize_t nh = n;
    {
      Handle pos = w.group(all.get(), "position");
      const hsize_t scalar_chunk = chunk_hint > 0 ? std::min<hsize_t>(chunk_hint, kScalarChunkRows) : kScalarChunkRows;
      step_ds = w.extendable(pos.get(), "step", H5T_STD_I64LE, {}, scalar_chunk);
      time_ds = w.extendable(pos.get(), "time", H5T_IEEE_F64LE, {}, scalar_chunk);
      position_value = w.extendable(pos.get(), "value", H5T_IEEE_F64LE, {nh, 3}, frames_per_chunk(n, 3, 8, chunk_hint));
    }
    {
      Handle g = w.group(box.get(), "edges");
      w.check_rc(H5Lcreate_hard(all.get(), "position/step", g.get(), "step", H5P_DEFAULT, H5P_DEFAULT), "link box step");
      w.check_rc(H5Lcreate_hard(all.get(), "position/time", g.get(), "time", H5P_DEFAULT, H5P_DEFAULT), "link box time");
      edges_value = w.extendable(g.get(), "value", H5T_IEEE_F64LE, {3, 3},
                                 chunk_hint > 0 ? std::min<hsize_t>(chunk_hint, 512) : 512);
    }
    image_value = element(all.get(), "image", H5T_STD_I32LE, {nh, 3}, 4);
    orientation_value = element(all.get(), "orientation", H5T_IEEE_F64LE, {nh, 4}, 8);
    species_value = element(all.get(), "species", H5T_STD_I32LE, {nh}, 4);
    id_value = element(all.get(), "id", H5T_STD_I64LE, {nh}, 8);
    frames_initialized = true;
  }

  Observable& observable(const std::string& name) {
    if (!valid_name(name)) throw RuntimeFailure("H5mdWriter: invalid observable name '" + name + "'");
    auto it = observables.find(name);
    if (it != observables.end()) return it->second;
    if (!observables_group.valid()) observables_group = w.group(file.get(), "observables");
    Observable o;
    o.group = w.group(observables_group.get(), name);
    return observables.emplace(name, std::move(o)).first->second;
  }

  void create_observable_datasets(Observable& o, const std::string& name, bool vector, std::size_t width) {
    o.vector = vector;
    o.width = width;
    o.step = w.extendable(o.group.get(), "step", H5T_STD_I64LE, {}, kScalarChunkRows);
    o.time = w.extendable(o.group.get(), "time", H5T_IEEE_F64LE, {}, kScalarChunkRows);
    if (vector) {
      o.value = w.extendable(o.group.get(), "value", H5T_IEEE_F64LE, {static_cast<hsize_t>(width)},
                             std::max<hsize_t>(1, kScalarChunkRows / width));
    } else {
      o.value = w.extendable(o.group.get(), "value", H5T_IEEE_F64LE, {}, kScalarChunkRows);
    }
    o.has_datasets = true;
    (void)name;
  }

  void flush_observable(Observable& o, const std::string& name) {
    const std::size_t rows = o.bstep.size();
    if (rows == 0) return;
    const std::string where = "/observables/" + name;
    w.append(o.step.get(), {}, o.rows, rows, H5T_NATIVE_INT64, o.bstep.data(), where + "/step");
    w.append(o.time.get(), {}, o.rows, rows, H5T_NATIVE_DOUBLE, o.btime.data(), where + "/time");
    if (o.vector) {
      w.append(o.value.get(), {static_cast<hsize_t>(o.width)}, o.rows, rows, H5T_NATIVE_DOUBLE, o.bvalue.data(),
               where + "/value");
    } else {
      w.append(o.value.get(), {}, o.rows, rows, H5T_NATIVE_DOUBLE, o.bvalue.data(), where + "/value");
    }
    o.rows += rows;
    o.bstep.clear();
    o.btime.clear();
    o.bvalue.clear();
  }

  void add_observable_row(const std::string& name, std::int64_t step, double time, const double* values,
                          std::size_t width, bool vector) {
    require_open();
    Observable& o = observable(name);
    if (!o.has_datasets) {
      if (vector && width == 0) throw RuntimeFailure("H5mdWriter: observable '" + name + "' has zero width");
      create_observable_datasets(o, name, vector, width);
    }
    if (o.vector != vector || o.width != width) {
      throw RuntimeFailure("H5mdWriter: observable '" + name + "' was started as " +
                           (o.vector ? "a vector of width " + std::to_string(o.width) : std::string("a scalar")) +
                           " but now gets " + (vector ? "a vector of width " + std::to_string(width) : std::string("a scalar")));
    }
    o.bstep.push_back(step);
    o.btime.push_back(time);
    o.bvalue.insert(o.bvalue.end(), values, values + width);
    if (o.bstep.size() >= kObservableBufferRows) flush_observable(o, name);
  }

  void flush_all() {
    for (auto& [name, o] : observables) flush_observable(o, name);
  }

  /// Closes every handle, then the file; afterwards the writer accepts no more calls.
  void close_file() {
    observables.clear();
    extra.clear();
    for (Handle* h : {&step_ds, &time_ds, &edges_value, &position_value, &image_value, &orientation_value,
                      &species_value, &id_value, &engine_state, &checkpoint_group, &anisodyn_group,
                      &observables_group, &parameters, &box, &all, &particles, &h5md}) {
      h->reset();
    }
    closed = true;
    if (!file.close()) w.fail("close file");
  }
};

H5mdWriter::H5mdWriter(const std::string& path, const H5mdHeader& header) {
  QuietHdf5 quiet;
  impl_ = std::make_unique<Impl>(path);
  Impl& m = *impl_;
  m.chunk_hint = header.frames_per_chunk;
  const WriteContext& w = m.w;

  m.file = Handle(w.check(H5Fcreate(m.out.partial_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create file"),
                  H5Fclose);
  hid_t f = m.file.get();

  m.h5md = w.group(f, "h5md");
  w.int_attribute(m.h5md.get(), "version", {1, 1}, false);
  {
    Handle creator = w.group(m.h5md.get(), "creator");
    w.string_attribute(creator.get(), "name", header.creator);
    w.string_attribute(creator.get(), "version",
                       header.creator_version.empty() ? std::string(anisodyn::kVersion) : header.creator_version);
    Handle author = w.group(m.h5md.get(), "author");
    w.string_attribute(author.get(), "name", header.author);
  }

  m.particles = w.group(f, "particles");
  m.all = w.group(m.particles.get(), kParticleGroup);
  m.box = w.group(m.all.get(), "box");
  w.int_attribute(m.box.get(), "dimension", {3}, true);
  w.string_array_attribute(m.box.get(), "boundary", {"periodic", "periodic", "periodic"});

  m.parameters = w.group(f, "parameters");
  w.string_dataset(m.parameters.get(), "config", header.parameters.is_null() ? "{}" : header.parameters.dump());
  w.string_dataset(m.parameters.get(), "provenance", header.provenance.is_null() ? "{}" : header.provenance.dump());
  if (!header.species.empty()) m.write_species_table(header.species);
}

H5mdWriter::H5mdWriter(H5mdWriter&&) noexcept = default;
H5mdWriter& H5mdWriter::operator=(H5mdWriter&&) noexcept = default;

H5mdWriter::~H5mdWriter() {
  if (!impl_) return;
  QuietHdf5 quiet;
  impl_.reset();  // closes every handle, then tool::AtomicOutput removes the partial file unless committed/suspended
}

const std::string& H5mdWriter::path() const { return impl_->path; }
const std::string& H5mdWriter::partial_path() const { return impl_->out.partial_path(); }
std::size_t H5mdWriter::frame_count() const { return impl_->frames; }

void H5mdWriter::append_frame(const State& s) { append_frame(s, {}); }

namespace {
/// N × 3 row-major copy of three component arrays.
std::vector<double> interleave(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c) {
  std::vector<double> out(3 * a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    out[3 * i] = a[i];
    out[3 * i + 1] = b[i];
    out[3 * i + 2] = c[i];
  }
  return out;
}
}  // namespace

void H5mdWriter::append_frame(const State& s, const std::vector<ParticleElement>& extra) {
  // Velocities and angular momenta, when the state carries them, are the per-particle elements
  // `velocity` (H5MD's name) and `angular_momentum`, [F, N, 3] like any engine-specific element.
  const Particles& p = s.particles;
  if (!p.has_velocities() && !p.has_angular_momenta()) return append_elements(s, extra);
  std::vector<ParticleElement> elements = extra;
  std::vector<double> v, l;
  if (p.has_velocities()) {
    v = interleave(p.vx, p.vy, p.vz);
    elements.push_back(ParticleElement{kVelocityElement, 3, v.data()});
  }
  if (p.has_angular_momenta()) {
    l = interleave(p.lx, p.ly, p.lz);
    elements.push_back(ParticleElement{kAngularMomentumElement, 3, l.data()});
  }
  append_elements(s, elements);
}

void H5mdWriter::append_elements(const State& s, const std::vector<ParticleElement>& extra) {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.require_open();
  const Particles& p = s.particles;
  const std::size_t n = p.size();
  if (!m.species_written) m.write_species_table(s.species);
  if (!m.frames_initialized) {
    m.initialize_frames(n);
    for (const auto& e : extra) {
      if (!valid_name(e.name) || e.width == 0) throw RuntimeFailure("H5mdWriter: invalid particle element '" + e.name + "'");
      m.extra[e.name] = Impl::Extra{m.element(m.all.get(), e.name, H5T_IEEE_F64LE, {static_cast<hsize_t>(n), e.width}, 8), e.width};
    }
  } else {
    if (n != m.n)
      throw RuntimeFailure("H5mdWriter: frame at step " + std::to_string(s.step) + " has " + std::to_string(n) +
                           " particles but the trajectory '" + m.path + "' has " + std::to_string(m.n) +
                           " (the particle count must be constant)");
    if (s.step < m.last_step)
      throw RuntimeFailure("H5mdWriter: frame step " + std::to_string(s.step) + " is before the previous frame's step " +
                           std::to_string(m.last_step));
  }
  if (p.y.size() != n || p.z.size() != n || p.ix.size() != n || p.iy.size() != n || p.iz.size() != n ||
      p.qw.size() != n || p.qx.size() != n || p.qy.size() != n || p.qz.size() != n || p.species.size() != n ||
      p.id.size() != n)
    throw RuntimeFailure("H5mdWriter: inconsistent particle arrays");
  for (std::size_t i = 0; i < n; ++i) {
    if (p.species[i] < 0 || static_cast<std::size_t>(p.species[i]) >= m.species.size())
      throw RuntimeFailure("H5mdWriter: particle " + std::to_string(i) + " has species " + std::to_string(p.species[i]) +
                           " but the species table has " + std::to_string(m.species.size()) + " entries");
  }

  const WriteContext& w = m.w;
  const hsize_t f = m.frames, nh = n;
  const std::int64_t step = s.step;
  const double time = s.time;
  w.append(m.step_ds.get(), {}, f, 1, H5T_NATIVE_INT64, &step, "/particles/all/position/step");
  w.append(m.time_ds.get(), {}, f, 1, H5T_NATIVE_DOUBLE, &time, "/particles/all/position/time");

  double edges[9] = {0};
  for (int k = 0; k < 3; ++k) edges[4 * k] = s.box.edges()[k];
  w.append(m.edges_value.get(), {3, 3}, f, 1, H5T_NATIVE_DOUBLE, edges, "/particles/all/box/edges/value");

  std::vector<double> buf(n * 4);
  for (std::size_t i = 0; i < n; ++i) {
    buf[3 * i] = p.x[i];
    buf[3 * i + 1] = p.y[i];
    buf[3 * i + 2] = p.z[i];
  }
  w.append(m.position_value.get(), {nh, 3}, f, 1, H5T_NATIVE_DOUBLE, buf.data(), "/particles/all/position/value");

  std::vector<std::int32_t> ibuf(n * 3);
  for (std::size_t i = 0; i < n; ++i) {
    ibuf[3 * i] = p.ix[i];
    ibuf[3 * i + 1] = p.iy[i];
    ibuf[3 * i + 2] = p.iz[i];
  }
  w.append(m.image_value.get(), {nh, 3}, f, 1, H5T_NATIVE_INT32, ibuf.data(), "/particles/all/image/value");

  for (std::size_t i = 0; i < n; ++i) {
    buf[4 * i] = p.qw[i];
    buf[4 * i + 1] = p.qx[i];
    buf[4 * i + 2] = p.qy[i];
    buf[4 * i + 3] = p.qz[i];
  }
  w.append(m.orientation_value.get(), {nh, 4}, f, 1, H5T_NATIVE_DOUBLE, buf.data(), "/particles/all/orientation/value");
  w.append(m.species_value.get(), {nh}, f, 1, H5T_NATIVE_INT32, p.species.data(), "/particles/all/species/value");
  w.append(m.id_value.get(), {nh}, f, 1, H5T_NATIVE_INT64, p.id.data(), "/particles/all/id/value");
  if (extra.size() != m.extra.size())
    throw RuntimeFailure("H5mdWriter: every frame must carry the same per-particle elements as the first");
  for (const auto& e : extra) {
    auto it = m.extra.find(e.name);
    if (it == m.extra.end() || it->second.width != e.width)
      throw RuntimeFailure("H5mdWriter: particle element '" + e.name + "' does not match the first frame's elements");
    w.append(it->second.value.get(), {nh, e.width}, f, 1, H5T_NATIVE_DOUBLE, e.data, "/particles/all/" + e.name + "/value");
  }

  m.frames += 1;
  m.last_step = s.step;
}

void H5mdWriter::append_observable(const std::string& name, std::int64_t step, double time, double value) {
  QuietHdf5 quiet;
  impl_->add_observable_row(name, step, time, &value, 1, false);
}

void H5mdWriter::append_observable(const std::string& name, std::int64_t step, double time,
                                   const std::vector<double>& values) {
  QuietHdf5 quiet;
  impl_->add_observable_row(name, step, time, values.data(), values.size(), true);
}

void H5mdWriter::set_observable_attribute(const std::string& name, const std::string& key, const std::string& value) {
  QuietHdf5 quiet;
  impl_->require_open();
  Impl::Observable& o = impl_->observable(name);
  impl_->w.string_attribute(o.group.get(), key, value);
}

void H5mdWriter::write_checkpoint(const nlohmann::json& engine_state) {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.require_open();
  const std::string text = engine_state.dump();
  if (!m.anisodyn_group.valid()) m.anisodyn_group = m.w.group(m.file.get(), "anisodyn");
  if (!m.checkpoint_group.valid()) m.checkpoint_group = m.w.group(m.anisodyn_group.get(), "checkpoint");
  if (!m.engine_state.valid()) {
    m.engine_state = m.w.string_dataset(m.checkpoint_group.get(), "engine_state", text);
  } else {
    m.w.write_string(m.engine_state.get(), text, "/anisodyn/checkpoint/engine_state");
  }
  m.flush_all();
  m.w.check_rc(H5Fflush(m.file.get(), H5F_SCOPE_GLOBAL), "flush");
}

void H5mdWriter::commit() {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.require_open();
  const WriteContext& w = m.w;
  if (!m.species_written) m.write_species_table({});
  m.flush_all();
  // Every observable gets datasets (an attribute-only observable becomes an empty scalar series).
  for (auto& [name, o] : m.observables) {
    if (!o.has_datasets) m.create_observable_datasets(o, name, false, 1);
  }
  // MDAnalysis reads /observables/<name>/value[frame] for every frame; series with fewer rows than
  // frames would make it fail, so they move to /anisodyn/observables (H5mdReader looks there too).
  std::vector<std::string> sparse;
  for (const auto& [name, o] : m.observables) {
    if (o.rows < m.frames) sparse.push_back(name);
  }
  if (!sparse.empty()) {
    if (!m.anisodyn_group.valid()) m.anisodyn_group = w.group(m.file.get(), "anisodyn");
    Handle target = H5Lexists(m.anisodyn_group.get(), "observables", H5P_DEFAULT) > 0
                        ? Handle(w.check(H5Gopen2(m.anisodyn_group.get(), "observables", H5P_DEFAULT), "open group"), H5Gclose)
                        : w.group(m.anisodyn_group.get(), "observables");
    for (const auto& name : sparse) {
      w.check_rc(H5Lmove(m.observables_group.get(), name.c_str(), target.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              "move observable " + name);
    }
    if (sparse.size() == m.observables.size()) {
      m.observables_group.reset();
      w.check_rc(H5Ldelete(m.file.get(), "observables", H5P_DEFAULT), "remove empty /observables");
    }
  }
  m.close_file();
  m.out.commit();
}

void H5mdWriter::suspend() {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.require_open();
  m.flush_all();
  m.close_file();
  m.out.keep_partial(true);
}

H5mdWriter::H5mdWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

namespace {
/// Number of leading entries of a non-decreasing step series that are ≤ last_step.
hsize_t rows_up_to(const std::vector<std::int64_t>& steps, std::int64_t last_step) {
  return static_cast<hsize_t>(std::upper_bound(steps.begin(), steps.end(), last_step) - steps.begin());
}
}  // namespace

/// Adds the names of the links in an HDF5 group to `names`.
static void insert_link_names(hid_t group, std::set<std::string>& names) {
  H5Literate(
      group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::set<std::string>*>(data)->insert(name);
        return 0;
      },
      &names);
}

/// Groups of /particles/all other than the standard H5MD elements that hold a `value` dataset.
static std::vector<std::string> extra_element_names(const FileReader& r) {
  const std::string all = std::string("/particles/") + kParticleGroup;
  Handle g = r.group(all);
  std::set<std::string> names;
  insert_link_names(g.get(), names);
  std::vector<std::string> out;
  for (const auto& name : names) {
    if (name == "box" || name == "position" || name == "image" || name == "orientation" || name == "species" ||
        name == "id" || name == "force")
      continue;
    if (r.exists(all + "/" + name + "/value")) out.push_back(name);
  }
  return out;
}

H5mdWriter H5mdWriter::resume(const std::string& path, std::int64_t last_step) {
  QuietHdf5 quiet;
  auto impl = std::make_unique<Impl>(path);  // checks that the directory is writable
  Impl& m = *impl;
  const std::string partial = m.out.partial_path();
  // If resuming fails, the partial file stays for inspection; once resumed it behaves as in a new run.
  m.out.keep_partial(true);
  std::error_code ec;
  if (!std::filesystem::exists(partial, ec))
    throw InputError(partial, "", "cannot resume: the partial output does not exist");
  if (H5Fis_hdf5(partial.c_str()) <= 0) throw InputError(partial, "", "cannot resume: not an HDF5 file");
  const hid_t f = H5Fopen(partial.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (f < 0) throw InputError(partial, "", "cannot resume: cannot open the partial output: " + hdf5_error_text());
  m.file = Handle(f, H5Fclose);
  const FileReader r{partial, f};
  const std::string all = std::string("/particles/") + kParticleGroup;

  m.h5md = r.group("/h5md");
  m.particles = r.group("/particles");
  m.all = r.group(all);
  m.box = r.group(all + "/box");
  m.parameters = r.group("/parameters");
  if (r.exists("/parameters/species")) {
    m.species = read_species_table(r);
    m.species_written = true;
  }

  if (r.exists(all + "/position")) {
    m.step_ds = r.dataset(all + "/position/step");
    m.time_ds = r.dataset(all + "/position/time");
    const auto steps = r.read_vector<std::int64_t>(all + "/position/step", H5T_NATIVE_INT64);
    const hsize_t keep = rows_up_to(steps, last_step);
    m.position_value = r.dataset(all + "/position/value");
    const auto d = dataset_dims(m.position_value.get());
    if (d.size() != 3 || d[2] != 3) r.bad(all + "/position/value", "expected shape [frames, N, 3], got " + dims_text(d));
    m.n = d[1];
    struct Element { Handle* handle; std::string hpath; std::vector<hsize_t> row; };
    const hsize_t nh = m.n;
    const std::vector<Element> elements{
        {&m.time_ds, all + "/position/time", {}},         {&m.position_value, all + "/position/value", {nh, 3}},
        {&m.edges_value, all + "/box/edges/value", {3, 3}}, {&m.image_value, all + "/image/value", {nh, 3}},
        {&m.orientation_value, all + "/orientation/value", {nh, 4}}, {&m.species_value, all + "/species/value", {nh}},
        {&m.id_value, all + "/id/value", {nh}}};
    std::vector<hsize_t> dims{keep};
    m.w.check_rc(H5Dset_extent(m.step_ds.get(), dims.data()), "truncate frames");
    for (const auto& e : elements) {
      if (!e.handle->valid()) *e.handle = r.dataset(e.hpath);
      const auto ed = dataset_dims(e.handle->get());
      std::vector<hsize_t> want{keep};
      want.insert(want.end(), e.row.begin(), e.row.end());
      if (ed.size() != want.size() || ed[0] < keep || !std::equal(ed.begin() + 1, ed.end(), want.begin() + 1))
        r.bad(e.hpath, "damaged partial output: shape " + dims_text(ed) + " does not match " + std::to_string(keep) +
                           " frames of " + std::to_string(m.n) + " particles");
      m.w.check_rc(H5Dset_extent(e.handle->get(), want.data()), "truncate " + e.hpath);
    }
    for (const auto& name : extra_element_names(r)) {
      Impl::Extra e;
      const std::string hpath = all + "/" + name + "/value";
      e.value = r.dataset(hpath);
      const auto ed = dataset_dims(e.value.get());
      if (ed.size() != 3 || ed[0] < keep || ed[1] != nh) r.bad(hpath, "damaged partial output: shape " + dims_text(ed));
      e.width = ed[2];
      const std::vector<hsize_t> want{keep, nh, ed[2]};
      m.w.check_rc(H5Dset_extent(e.value.get(), want.data()), "truncate " + hpath);
      m.extra.emplace(name, std::move(e));
    }
    m.frames = keep;
    m.last_step = keep > 0 ? steps[keep - 1] : 0;
    m.frames_initialized = true;
  }

  if (r.exists("/observables")) {
    m.observables_group = r.group("/observables");
    std::set<std::string> names;
    insert_link_names(m.observables_group.get(), names);
    for (const auto& name : names) {
      const std::string base = "/observables/" + name;
      Impl::Observable o;
      o.group = r.group(base);
      if (r.exists(base + "/step")) {
        o.step = r.dataset(base + "/step");
        o.time = r.dataset(base + "/time");
        o.value = r.dataset(base + "/value");
        const auto steps = r.read_vector<std::int64_t>(base + "/step", H5T_NATIVE_INT64);
        const hsize_t keep = rows_up_to(steps, last_step);
        const auto vd = dataset_dims(o.value.get());
        if (vd.empty() || vd.size() > 2 || vd[0] < keep) r.bad(base + "/value", "damaged partial output: shape " + dims_text(vd));
        o.vector = vd.size() == 2;
        o.width = o.vector ? vd[1] : 1;
        std::vector<hsize_t> want{keep};
        m.w.check_rc(H5Dset_extent(o.step.get(), want.data()), "truncate " + base);
        m.w.check_rc(H5Dset_extent(o.time.get(), want.data()), "truncate " + base);
        if (o.vector) want.push_back(o.width);
        m.w.check_rc(H5Dset_extent(o.value.get(), want.data()), "truncate " + base);
        o.rows = keep;
        o.has_datasets = true;
      }
      m.observables.emplace(name, std::move(o));
    }
  }
  if (r.exists("/anisodyn")) m.anisodyn_group = r.group("/anisodyn");
  if (r.exists("/anisodyn/checkpoint")) m.checkpoint_group = r.group("/anisodyn/checkpoint");
  if (r.exists("/anisodyn/checkpoint/engine_state")) m.engine_state = r.dataset("/anisodyn/checkpoint/engine_state");

  m.out.keep_partial(false);
  return H5mdWriter(std::move(impl));
}

// =====================================================================================================
// Reader
// =====================================================================================================

struct H5mdReader::Impl : FileReader {
  Handle file;
  std::size_t frames = 0, n = 0;
  bool has_positions = false;

  /// Row `frame` of /particles/all/<element>/value, whose shape must be [frames, N(, width)].
  void read_particle_row(const std::string& element, std::size_t frame, std::size_t width, hid_t mem_type,
                         void* out) const {
    const std::string hpath = std::string("/particles/") + kParticleGroup + "/" + element + "/value";
    Handle ds = dataset(hpath);
    const auto d = dataset_dims(ds.get());
    const bool shape_ok = width == 0 ? (d.size() == 2 && d[1] == n) : (d.size() == 3 && d[1] == n && d[2] == width);
    if (!shape_ok) {
      bad(hpath, "expected shape [frames, " + std::to_string(n) + (width ? ", " + std::to_string(width) : "") +
                     "], got " + dims_text(d));
    }
    if (frame >= d[0]) bad(hpath, "has " + std::to_string(d[0]) + " frames, frame " + std::to_string(frame) + " requested");
    std::vector<hsize_t> start{frame, 0}, count{1, n};
    if (width) { start.push_back(0); count.push_back(width); }
    read_block(ds.get(), start, count, mem_type, out, hpath);
  }

};

H5mdReader::H5mdReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.path = path;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "", "cannot open file: No such file or directory");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "cannot open file: it is a directory");
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 == 0) throw InputError(path, "", "not an HDF5 file");
  if (is_hdf5 < 0) throw InputError(path, "", "cannot open file: " + hdf5_error_text());
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw InputError(path, "", "cannot open HDF5 file: " + hdf5_error_text());
  m.file = Handle(f, H5Fclose);
  m.fid = f;

  if (!m.exists("/h5md")) m.bad("/h5md", "missing required group (not an H5MD file)");
  const std::string all = std::string("/particles/") + kParticleGroup;
  m.group(all);
  m.group(all + "/box");
  const std::string pos = all + "/position/value";
  if (m.exists(all + "/position")) {
    Handle ds = m.dataset(pos);
    const auto d = dataset_dims(ds.get());
    if (d.size() != 3 || d[2] != 3) m.bad(pos, "expected shape [frames, N, 3], got " + dims_text(d));
    m.frames = d[0];
    m.n = d[1];
    m.has_positions = true;
  }
}

H5mdReader::H5mdReader(H5mdReader&&) noexcept = default;
H5mdReader& H5mdReader::operator=(H5mdReader&&) noexcept = default;
H5mdReader::~H5mdReader() {
  if (!impl_) return;
  QuietHdf5 quiet;
  impl_.reset();
}

const std::string& H5mdReader::path() const { return impl_->path; }
std::size_t H5mdReader::frame_count() const { return impl_->frames; }
std::size_t H5mdReader::particle_count() const { return impl_->n; }

SpeciesTable H5mdReader::species() const {
  QuietHdf5 quiet;
  return read_species_table(*impl_);
}

std::vector<std::int64_t> H5mdReader::frame_steps() const {
  QuietHdf5 quiet;
  if (!impl_->has_positions) return {};
  return impl_->read_vector<std::int64_t>(std::string("/particles/") + kParticleGroup + "/position/step", H5T_NATIVE_INT64);
}

std::vector<double> H5mdReader::frame_times() const {
  QuietHdf5 quiet;
  if (!impl_->has_positions) return {};
  return impl_->read_vector<double>(std::string("/particles/") + kParticleGroup + "/position/time", H5T_NATIVE_DOUBLE);
}

State H5mdReader::read_frame(std::ptrdiff_t index) const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  const std::string all = std::string("/particles/") + kParticleGroup;
  if (!m.has_positions) m.bad(all + "/position", "missing required group (the file holds no frames)");
  if (m.frames == 0) m.bad(all + "/position/value", "the file holds no frames");
  const auto f = static_cast<std::ptrdiff_t>(m.frames);
  const std::ptrdiff_t idx = index < 0 ? f + index : index;
  if (idx < 0 || idx >= f)
    m.bad(all + "/position/value",
          "frame " + std::to_string(index) + " is out of range (the file holds " + std::to_string(f) + " frames)");
  const auto frame = static_cast<std::size_t>(idx);
  const std::size_t n = m.n;

  State s;
  s.species = species();

  // step and time of the frame
  for (const char* what : {"step", "time"}) {
    const std::string hpath = all + "/position/" + what;
    Handle ds = m.dataset(hpath);
    const auto d = dataset_dims(ds.get());
    if (d.size() != 1 || d[0] < m.frames) m.bad(hpath, "expected shape [" + std::to_string(m.frames) + "], got " + dims_text(d));
    if (what[0] == 's') m.read_block(ds.get(), {frame}, {1}, H5T_NATIVE_INT64, &s.step, hpath);
    else m.read_block(ds.get(), {frame}, {1}, H5T_NATIVE_DOUBLE, &s.time, hpath);
  }

  // box: edges as a vector [frames, 3] or a (diagonal) matrix [frames, 3, 3]
  {
    const std::string hpath = all + "/box/edges/value";
    Handle ds = m.dataset(hpath);
    const auto d = dataset_dims(ds.get());
    Vec3 L;
    if (d.size() == 2 && d[1] == 3) {
      if (frame >= d[0]) m.bad(hpath, "has " + std::to_string(d[0]) + " frames, frame " + std::to_string(frame) + " requested");
      double e[3];
      m.read_block(ds.get(), {frame, 0}, {1, 3}, H5T_NATIVE_DOUBLE, e, hpath);
      L = Vec3(e[0], e[1], e[2]);
    } else if (d.size() == 3 && d[1] == 3 && d[2] == 3) {
      if (frame >= d[0]) m.bad(hpath, "has " + std::to_string(d[0]) + " frames, frame " + std::to_string(frame) + " requested");
      double e[9];
      m.read_block(ds.get(), {frame, 0, 0}, {1, 3, 3}, H5T_NATIVE_DOUBLE, e, hpath);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (a != b && e[3 * a + b] != 0.0) m.bad(hpath, "only orthorhombic boxes are supported (off-diagonal edge components found)");
      L = Vec3(e[0], e[4], e[8]);
    } else {
      m.bad(hpath, "expected shape [frames, 3] or [frames, 3, 3], got " + dims_text(d));
    }
    if (!(L.minCoeff() > 0)) m.bad(hpath, "box edges must be positive");
    s.box.set_edges(L);
  }

  Particles& p = s.particles;
  std::vector<double> buf(n * 4);
  m.read_particle_row("position", frame, 3, H5T_NATIVE_DOUBLE, buf.data());
  p.x.resize(n); p.y.resize(n); p.z.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.x[i] = buf[3 * i];
    p.y[i] = buf[3 * i + 1];
    p.z[i] = buf[3 * i + 2];
  }
  std::vector<std::int32_t> ibuf(n * 3);
  m.read_particle_row("image", frame, 3, H5T_NATIVE_INT32, ibuf.data());
  p.ix.resize(n); p.iy.resize(n); p.iz.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.ix[i] = ibuf[3 * i];
    p.iy[i] = ibuf[3 * i + 1];
    p.iz[i] = ibuf[3 * i + 2];
  }
  m.read_particle_row("orientation", frame, 4, H5T_NATIVE_DOUBLE, buf.data());
  p.qw.resize(n); p.qx.resize(n); p.qy.resize(n); p.qz.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.qw[i] = buf[4 * i];
    p.qx[i] = buf[4 * i + 1];
    p.qy[i] = buf[4 * i + 2];
    p.qz[i] = buf[4 * i + 3];
  }
  p.species.resize(n);
  m.read_particle_row("species", frame, 0, H5T_NATIVE_INT32, p.species.data());
  p.id.resize(n);
  m.read_particle_row("id", frame, 0, H5T_NATIVE_INT64, p.id.data());
  read_motion(p, frame);

  for (std::size_t i = 0; i < n; ++i) {
    if (p.species[i] < 0 || static_cast<std::size_t>(p.species[i]) >= s.species.size())
      m.bad(all + "/species/value", "particle " + std::to_string(i) + " has species " + std::to_string(p.species[i]) +
                                        ", which is not in /parameters/species (" + std::to_string(s.species.size()) +
                                        " species)");
  }
  return s;
}

std::vector<double> H5mdReader::read_element_frames(const std::string& element, std::size_t& width) const {
  return read_element_frames(element, width, FrameSlice{0, impl_->frames, 1});
}

std::vector<std::int64_t> H5mdReader::read_integer_element_frames(const std::string& element) const {
  return read_integer_element_frames(element, FrameSlice{0, impl_->frames, 1});
}

namespace {

/// Frames `frames` of /particles/all/<element>/value, whose shape must be [F, N] (width == nullptr)
/// or [F, N, width] (the width is returned).
template <class T>
std::vector<T> read_element_rows(const FileReader& m, std::size_t file_frames, std::size_t n, const std::string& element,
                                 hid_t mem_type, const FrameSlice& frames, std::size_t* width) {
  const std::string hpath = std::string("/particles/") + kParticleGroup + "/" + element + "/value";
  if (!m.exists(hpath)) m.bad(hpath, "missing required dataset (per-particle element '" + element + "')");
  const auto d = m.dims(hpath);
  const std::size_t rank = width ? 3 : 2;
  if (d.size() != rank || d[0] != file_frames || d[1] != n)
    m.bad(hpath, "expected shape [" + std::to_string(file_frames) + ", " + std::to_string(n) + (width ? ", width" : "") + "], got " +
                     dims_text(d));
  if (frames.count > 0 && (frames.stride == 0 || frames.frame(frames.count - 1) >= file_frames))
    m.bad(hpath, "frames " + std::to_string(frames.first) + " … " + std::to_string(frames.frame(frames.count - 1)) +
                     " requested, the file holds " + std::to_string(file_frames));
  if (width) *width = d[2];
  return m.read_frame_rows<T>(hpath, mem_type, frames);
}

}  // namespace

std::vector<double> H5mdReader::read_element_frames(const std::string& element, std::size_t& width, const FrameSlice& frames) const {
  QuietHdf5 quiet;
  return read_element_rows<double>(*impl_, impl_->frames, impl_->n, element, H5T_NATIVE_DOUBLE, frames, &width);
}

std::vector<std::int64_t> H5mdReader::read_integer_element_frames(const std::string& element, const FrameSlice& frames) const {
  QuietHdf5 quiet;
  return read_element_rows<std::int64_t>(*impl_, impl_->frames, impl_->n, element, H5T_NATIVE_INT64, frames, nullptr);
}

std::vector<double> H5mdReader::box_edges_frames() const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  const std::string hpath = std::string("/particles/") + kParticleGroup + "/box/edges/value";
  std::vector<hsize_t> d;
  const auto raw = m.read_vector<double>(hpath, H5T_NATIVE_DOUBLE, &d);
  const bool vector_form = d.size() == 2 && d[1] == 3;
  const bool matrix_form = d.size() == 3 && d[1] == 3 && d[2] == 3;
  if (!(vector_form || matrix_form) || d[0] < m.frames)
    m.bad(hpath, "expected shape [" + std::to_string(m.frames) + ", 3] or [" + std::to_string(m.frames) + ", 3, 3], got " + dims_text(d));
  std::vector<double> out(3 * m.frames);
  for (std::size_t f = 0; f < m.frames; ++f)
    for (int a = 0; a < 3; ++a) {
      out[3 * f + a] = vector_form ? raw[3 * f + a] : raw[9 * f + 4 * a];
      if (!(out[3 * f + a] > 0)) m.bad(hpath, "box edges must be positive (frame " + std::to_string(f) + ")");
    }
  return out;
}

std::vector<std::string> H5mdReader::particle_element_names() const {
  QuietHdf5 quiet;
  return extra_element_names(*impl_);
}

void H5mdReader::read_motion(Particles& p, std::size_t frame) const {
  auto read_vectors = [&](const char* name, std::vector<double>& a, std::vector<double>& b, std::vector<double>& c) {
    std::size_t width = 0;
    const std::vector<double> rows = read_particle_element(name, static_cast<std::ptrdiff_t>(frame), width);
    if (width != 3)
      impl_->bad(std::string("/particles/") + kParticleGroup + "/" + name + "/value",
                 "expected 3 components per particle, got " + std::to_string(width));
    for (std::size_t i = 0; i < p.size(); ++i) {
      a[i] = rows[3 * i];
      b[i] = rows[3 * i + 1];
      c[i] = rows[3 * i + 2];
    }
  };
  auto stored = [&](const char* name) { return impl_->exists(std::string("/particles/") + kParticleGroup + "/" + name + "/value"); };
  if (stored(kVelocityElement)) {
    p.carry_velocities();
    read_vectors(kVelocityElement, p.vx, p.vy, p.vz);
  }
  if (stored(kAngularMomentumElement)) {
    p.carry_angular_momenta();
    read_vectors(kAngularMomentumElement, p.lx, p.ly, p.lz);
  }
}

std::vector<double> H5mdReader::read_particle_element(const std::string& name, std::ptrdiff_t index, std::size_t& width) const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  const std::string hpath = std::string("/particles/") + kParticleGroup + "/" + name + "/value";
  if (!m.exists(hpath)) m.bad(hpath, "missing per-particle element '" + name + "'");
  Handle ds = m.dataset(hpath);
  const auto d = dataset_dims(ds.get());
  if (d.size() != 3) m.bad(hpath, "expected shape [frames, N, width], got " + dims_text(d));
  width = d[2];
  const auto f = static_cast<std::ptrdiff_t>(d[0]);
  const std::ptrdiff_t idx = index < 0 ? f + index : index;
  if (idx < 0 || idx >= f) m.bad(hpath, "frame " + std::to_string(index) + " is out of range");
  std::vector<double> out(m.n * width);
  m.read_particle_row(name, static_cast<std::size_t>(idx), width, H5T_NATIVE_DOUBLE, out.data());
  return out;
}

bool H5mdReader::has_observable(const std::string& name) const {
  QuietHdf5 quiet;
  return !impl_->observable_path(name).empty();
}

std::vector<std::string> H5mdReader::observable_names() const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  std::set<std::string> names;
  for (const std::string base : {"/observables", "/anisodyn/observables"}) {
    if (!m.exists(base)) continue;
    Handle g = m.group(base);
    insert_link_names(g.get(), names);
  }
  return {names.begin(), names.end()};
}

H5mdReader::Series H5mdReader::read_observable(const std::string& name) const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  const std::string base = m.observable_path(name);
  if (base.empty()) m.bad("/observables/" + name, "no such observable");
  Series out;
  std::vector<hsize_t> ds, dt, dv;
  out.step = m.read_vector<std::int64_t>(base + "/step", H5T_NATIVE_INT64, &ds);
  out.time = m.read_vector<double>(base + "/time", H5T_NATIVE_DOUBLE, &dt);
  out.value = m.read_vector<double>(base + "/value", H5T_NATIVE_DOUBLE, &dv);
  if (ds.size() != 1) m.bad(base + "/step", "expected a one-dimensional dataset, got shape " + dims_text(ds));
  const hsize_t rows = ds[0];
  if (dt.size() != 1 || dt[0] != rows) m.bad(base + "/time", "expected shape [" + std::to_string(rows) + "], got " + dims_text(dt));
  if (dv.size() == 1 && dv[0] == rows) {
    out.width = 1;
  } else if (dv.size() == 2 && dv[0] == rows) {
    out.width = dv[1];
  } else {
    m.bad(base + "/value", "expected shape [" + std::to_string(rows) + "] or [" + std::to_string(rows) + ", width], got " +
                               dims_text(dv));
  }
  return out;
}

std::optional<std::string> H5mdReader::observable_attribute(const std::string& name, const std::string& key) const {
  QuietHdf5 quiet;
  const Impl& m = *impl_;
  const std::string base = m.observable_path(name);
  if (base.empty()) m.bad("/observables/" + name, "no such observable");
  Handle g = m.group(base);
  if (H5Aexists(g.get(), key.c_str()) <= 0) return std::nullopt;
  Handle attr(H5Aopen(g.get(), key.c_str(), H5P_DEFAULT), H5Aclose);
  return read_string_from(attr.get(), true, m.path, base + "@" + key);
}

nlohmann::json H5mdReader::parameters() const {
  QuietHdf5 quiet;
  return impl_->read_json("/parameters/config");
}

nlohmann::json H5mdReader::provenance() const {
  QuietHdf5 quiet;
  return impl_->read_json("/parameters/provenance");
}

std::optional<nlohmann::json> H5mdReader::checkpoint() const {
  QuietHdf5 quiet;
  const std::string hpath = "/anisodyn/checkpoint/engine_state";
  if (!impl_->exists(hpath)) return std::nullopt;
  return impl_->read_json(hpath);
}

// =====================================================================================================
// Checkpoint files
// =====================================================================================================

void write_checkpoint_file(const std::string& path, const H5mdHeader& header, const State& state,
                           const nlohmann::json& engine_state) {
  H5mdHeader h = header;
  if (h.species.empty()) h.species = state.species;
  h.frames_per_chunk = 1;
  H5mdWriter writer(path, h);
  writer.append_frame(state);
  writer.write_checkpoint(engine_state);
  writer.commit();
}

std::pair<State, nlohmann::json> read_checkpoint_file(const std::string& path) {
  H5mdReader reader(path);
  auto engine_state = reader.checkpoint();
  if (!engine_state)
    throw InputError(path, "/anisodyn/checkpoint/engine_state", "missing required dataset (not a checkpoint file)");
  return {reader.read_frame(-1), std::move(*engine_state)};
}

}  // namespace anisodyn::io
