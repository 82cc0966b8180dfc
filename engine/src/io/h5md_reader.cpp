// H5MD 1.1 reader on the HDF5 C API (include/anisodyn/io/h5md.hpp, docs/file-format.md).
#include "anisodyn/io/h5md.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/version.hpp"
#include "h5md_layout.hpp"

namespace anisodyn::io {

using namespace detail;
using namespace h5md_layout;
using nlohmann::json;

namespace {
/// Row-major rows of width columns.size() into one array per column (each resized to n).
template <class T, std::size_t W>
void split_columns(const T* rows, std::size_t n, const std::array<std::vector<T>*, W>& columns) {
  for (auto* c : columns) c->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < W; ++k) (*columns[k])[i] = rows[W * i + k];
}
}  // namespace

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
  split_columns<double, 3>(buf.data(), n, {&p.x, &p.y, &p.z});
  std::vector<std::int32_t> ibuf(n * 3);
  m.read_particle_row("image", frame, 3, H5T_NATIVE_INT32, ibuf.data());
  split_columns<std::int32_t, 3>(ibuf.data(), n, {&p.ix, &p.iy, &p.iz});
  m.read_particle_row("orientation", frame, 4, H5T_NATIVE_DOUBLE, buf.data());
  split_columns<double, 4>(buf.data(), n, {&p.qw, &p.qx, &p.qy, &p.qz});
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
  return m.read_frame_rows<T>(hpath, mem_type, frames.first, frames.count, frames.stride);
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
    split_columns<double, 3>(rows.data(), p.size(), {&a, &b, &c});
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
  return !observable_path(*impl_, name).empty();
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
  const std::string base = observable_path(m, name);
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
  const std::string base = observable_path(m, name);
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

std::vector<double> H5mdReader::checkpoint_array(const std::string& name) const {
  QuietHdf5 quiet;
  const std::string hpath = "/anisodyn/checkpoint/arrays/" + name;
  Handle ds = impl_->dataset(hpath);
  const auto dims = impl_->dims(hpath);
  if (dims.size() != 1) impl_->bad(hpath, "expected a one-dimensional array");
  std::vector<double> out(dims[0]);
  if (!out.empty()) impl_->read_all(ds.get(), H5T_NATIVE_DOUBLE, out.data(), hpath);
  return out;
}

}  // namespace anisodyn::io
