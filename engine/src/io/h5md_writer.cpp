// H5MD 1.1 writer on the HDF5 C API. See include/anisodyn/io/h5md.hpp and docs/file-format.md for
// the layout; the comments here explain only implementation choices.
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
#include "h5md_layout.hpp"

namespace anisodyn::io {

using namespace detail;
using namespace h5md_layout;
using nlohmann::json;

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
    std::vector<std::string> names, shapes, specs;
    std::vector<double> edges, diameter, length, mass, dt, dr;
    for (const auto& s : table) {
      names.push_back(s.name);
      shapes.push_back(shape_kind_name(s.shape.kind));
      specs.push_back(s.shape.spec().dump());
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
    w.string_array_dataset(g.get(), "shape_spec", specs);
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

void H5mdWriter::write_checkpoint_array(const std::string& name, const std::vector<double>& values) {
  QuietHdf5 quiet;
  Impl& m = *impl_;
  m.require_open();
  if (!m.anisodyn_group.valid()) m.anisodyn_group = m.w.group(m.file.get(), "anisodyn");
  if (!m.checkpoint_group.valid()) m.checkpoint_group = m.w.group(m.anisodyn_group.get(), "checkpoint");
  const hid_t parent = m.checkpoint_group.get();
  Handle arrays = H5Lexists(parent, "arrays", H5P_DEFAULT) > 0
                      ? Handle(m.w.check(H5Gopen2(parent, "arrays", H5P_DEFAULT), "open group arrays"), H5Gclose)
                      : m.w.group(parent, "arrays");
  if (H5Lexists(arrays.get(), name.c_str(), H5P_DEFAULT) > 0)
    m.w.check_rc(H5Ldelete(arrays.get(), name.c_str(), H5P_DEFAULT), "replace checkpoint array " + name);
  m.w.double_dataset(arrays.get(), name, values);
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

}  // namespace anisodyn::io
