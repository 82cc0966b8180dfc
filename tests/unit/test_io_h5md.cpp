// io: H5MD round trips (bit-for-bit), observables, checkpoints and error reporting for bad files.
#include <gtest/gtest.h>

#include "input_error.hpp"
#include "scratch_dir.hpp"
#include <hdf5.h>

#include <stdlib.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

class H5md : public anisodyn::testing_support::ScratchDirTest {
 protected:
  H5md() : ScratchDirTest("io-h5md") {}
};

SpeciesTable two_species() {
  Species board;
  board.name = "board";
  board.shape = Shape::cuboid(1.0, 3.0, 12.0);
  board.mass = 2.5;
  board.D_trans = Vec3(0.0123, 0.0456, 0.0789);
  board.D_rot = Vec3(1.0 / 3.0, 0.001, std::nextafter(0.5, 1.0));
  Species rod;
  rod.name = "rod";
  rod.shape = Shape::spherocylinder(5.0, 1.0);
  rod.D_trans = Vec3(0.1, 0.1, 0.2);
  rod.D_rot = Vec3(0.03, 0.03, 0.0);
  return {board, rod};
}

/// A random two-species state: wrapped positions (including values right below L), random images,
/// random unit quaternions, shuffled ids.
State random_state(Rng& rng, std::size_t n, const Vec3& L, std::int64_t step, double time) {
  State s;
  s.species = two_species();
  s.box = Box(L);
  s.step = step;
  s.time = time;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 r(rng.uniform(0, L.x()), rng.uniform(0, L.y()), rng.uniform(0, L.z()));
    if (i == 0) r = Vec3(std::nextafter(L.x(), 0.0), 0.0, std::numeric_limits<double>::denorm_min());
    s.particles.add(static_cast<int>(rng.index(2)), r, uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()),
                    static_cast<std::int64_t>(1000 * n - 7 * i));
    s.particles.set_image(i, Int3(static_cast<int>(rng.index(7)) - 3, static_cast<int>(rng.index(100000)) - 50000,
                                  std::numeric_limits<std::int32_t>::min() + static_cast<int>(i)));
  }
  return s;
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_same_state(const State& a, const State& b) {
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(bits(a.time), bits(b.time));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(a.box.edges()[k]), bits(b.box.edges()[k]));
  const Particles &p = a.particles, &q = b.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(bits(p.x[i]), bits(q.x[i])) << i;
    EXPECT_EQ(bits(p.y[i]), bits(q.y[i])) << i;
    EXPECT_EQ(bits(p.z[i]), bits(q.z[i])) << i;
    EXPECT_EQ(bits(p.qw[i]), bits(q.qw[i])) << i;
    EXPECT_EQ(bits(p.qx[i]), bits(q.qx[i])) << i;
    EXPECT_EQ(bits(p.qy[i]), bits(q.qy[i])) << i;
    EXPECT_EQ(bits(p.qz[i]), bits(q.qz[i])) << i;
    EXPECT_EQ(p.ix[i], q.ix[i]);
    EXPECT_EQ(p.iy[i], q.iy[i]);
    EXPECT_EQ(p.iz[i], q.iz[i]);
    EXPECT_EQ(p.species[i], q.species[i]);
    EXPECT_EQ(p.id[i], q.id[i]);
  }
  ASSERT_EQ(p.has_velocities(), q.has_velocities());
  ASSERT_EQ(p.has_angular_momenta(), q.has_angular_momenta());
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      if (p.has_velocities()) EXPECT_EQ(bits(p.velocity(i)[k]), bits(q.velocity(i)[k])) << i;
      if (p.has_angular_momenta()) EXPECT_EQ(bits(p.angular_momentum(i)[k]), bits(q.angular_momentum(i)[k])) << i;
    }
  ASSERT_EQ(a.species.size(), b.species.size());
  for (std::size_t k = 0; k < a.species.size(); ++k) {
    const Species &s = a.species[k], &t = b.species[k];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.shape.kind, t.shape.kind);
    EXPECT_EQ(s.shape.diameter, t.shape.diameter);
    EXPECT_EQ(s.shape.length, t.shape.length);
    EXPECT_EQ(s.mass, t.mass);
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(bits(s.shape.edges[d]), bits(t.shape.edges[d]));
      EXPECT_EQ(bits(s.D_trans[d]), bits(t.D_trans[d]));
      EXPECT_EQ(bits(s.D_rot[d]), bits(t.D_rot[d]));
    }
  }
}

using anisodyn::testing_support::input_error;

/// Deletes an HDF5 link in a finished file (to fabricate damaged inputs).
void delete_link(const std::string& path, const std::string& link) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, link.c_str(), H5P_DEFAULT), 0);
  H5Fclose(f);
}

bool link_exists(const std::string& path, const std::string& link) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const bool e = H5Lexists(f, link.c_str(), H5P_DEFAULT) > 0;
  H5Fclose(f);
  return e;
}

io::H5mdHeader header_for(const State& s) {
  io::H5mdHeader h;
  h.parameters = {{"engine", "mc"}, {"pressure", 1.25}, {"species", {{{"name", "board"}}}}};
  h.provenance = {{"tool", "test"}, {"inputs", json::array()}};
  h.species = s.species;
  return h;
}

}  // namespace

TEST_F(H5md, RoundTripThreeFramesWithChangingBoxIsBitForBit) {
  Rng rng(2024, 1);
  const std::size_t n = 73;
  std::vector<State> frames;
  frames.push_back(random_state(rng, n, Vec3(20.0, 21.5, 30.25), 0, 0.0));
  frames.push_back(random_state(rng, n, Vec3(19.731, 21.2, 29.9) * (1.0 + 1e-13), 1000, 0.1 * 3));
  frames.push_back(random_state(rng, n, Vec3(M_PI * 6, std::sqrt(500.0), 29.0), 2500, 1.0 / 3.0));

  const std::string path = file("traj.h5");
  io::H5mdWriter w(path, header_for(frames[0]));
  for (const auto& s : frames) w.append_frame(s);
  EXPECT_EQ(w.frame_count(), 3u);
  w.commit();

  io::H5mdReader r(path);
  ASSERT_EQ(r.frame_count(), 3u);
  EXPECT_EQ(r.particle_count(), n);
  for (std::size_t f = 0; f < 3; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    expect_same_state(frames[f], r.read_frame(static_cast<std::ptrdiff_t>(f)));
  }
  expect_same_state(frames[2], r.read_frame(-1));
  expect_same_state(frames[0], r.read_frame(-3));
  EXPECT_EQ(r.frame_steps(), (std::vector<std::int64_t>{0, 1000, 2500}));
  EXPECT_EQ(r.frame_times()[2], 1.0 / 3.0);
  EXPECT_EQ(r.parameters(), header_for(frames[0]).parameters);
  EXPECT_EQ(r.provenance()["tool"], "test");
  EXPECT_FALSE(r.checkpoint().has_value());

  const InputError out_of_range = input_error([&] { r.read_frame(3); });
  EXPECT_EQ(out_of_range.json_path(), "/particles/all/position/value");
  EXPECT_THROW(r.read_frame(-4), InputError);
}

/// The state with random velocities and (optionally) angular momenta, as an MD-type engine has.
State in_motion(State s, Rng& rng, bool angular) {
  s.particles.carry_velocities();
  if (angular) s.particles.carry_angular_momenta();
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    s.particles.set_velocity(i, Vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), 1.0 / (3.0 + static_cast<double>(i))));
    if (angular) s.particles.set_angular_momentum(i, Vec3(rng.uniform(-1, 1), -0.0, std::nextafter(1.0, 2.0)));
  }
  return s;
}

TEST_F(H5md, VelocitiesAndAngularMomentaRoundTripThroughFramesCheckpointsAndResume) {
  Rng rng(31, 7);
  std::vector<State> frames;
  for (int f = 0; f < 3; ++f) frames.push_back(in_motion(random_state(rng, 17, Vec3(10, 11, 12), 50 * f, 0.25 * f), rng, true));
  const std::string path = file("md.h5");
  {
    io::H5mdWriter w(path, header_for(frames[0]));
    w.append_frame(frames[0]);
    w.append_frame(frames[1]);
    w.write_checkpoint({{"step", 50}});
    w.suspend();
  }
  {
    io::H5mdWriter w = io::H5mdWriter::resume(path, 50);
    w.append_frame(frames[2]);
    w.commit();
  }
  io::H5mdReader r(path);
  for (std::size_t f = 0; f < 3; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    expect_same_state(frames[f], r.read_frame(static_cast<std::ptrdiff_t>(f)));
  }
  // Stored where H5MD puts velocities; the angular momentum beside it.
  EXPECT_TRUE(link_exists(path, "/particles/all/velocity/value"));
  EXPECT_TRUE(link_exists(path, "/particles/all/angular_momentum/value"));
  std::size_t width = 0;
  EXPECT_EQ(r.read_element_frames("velocity", width).size(), 3u * 17u * 3u);
  EXPECT_EQ(width, 3u);

  // A one-frame checkpoint file keeps them too, so an MD run restarts exactly.
  io::write_checkpoint_file(file("md.checkpoint.h5"), header_for(frames[1]), frames[1], {{"step", 50}});
  expect_same_state(frames[1], io::read_checkpoint_file(file("md.checkpoint.h5")).first);

  // Velocities without angular momenta (point particles); and a state with neither writes neither.
  const State point = in_motion(random_state(rng, 5, Vec3(9, 9, 9), 0, 0), rng, false);
  {
    io::H5mdWriter w(file("points.h5"), header_for(point));
    w.append_frame(point);
    w.commit();
  }
  expect_same_state(point, io::H5mdReader(file("points.h5")).read_frame(0));
  EXPECT_FALSE(link_exists(file("points.h5"), "/particles/all/angular_momentum"));
  const State still = random_state(rng, 5, Vec3(9, 9, 9), 0, 0);
  {
    io::H5mdWriter w(file("still.h5"), header_for(still));
    w.append_frame(still);
    w.commit();
  }
  EXPECT_FALSE(link_exists(file("still.h5"), "/particles/all/velocity"));
  EXPECT_FALSE(io::H5mdReader(file("still.h5")).read_frame(0).particles.has_velocities());
}

TEST_F(H5md, LayoutFollowsH5mdAndMDAnalysisExpectations) {
  Rng rng(5, 0);
  const State s = random_state(rng, 10, Vec3(9, 10, 11), 7, 0.5);
  const std::string path = file("layout.h5");
  io::H5mdWriter w(path, header_for(s));
  w.append_frame(s);
  w.commit();
  for (const char* link : {"/h5md/creator", "/h5md/author", "/particles/all/box/edges/value", "/particles/all/position/step",
                           "/particles/all/position/time", "/particles/all/image/value", "/particles/all/orientation/value",
                           "/particles/all/species/step", "/particles/all/id/time", "/parameters/config",
                           "/parameters/provenance", "/parameters/species/D_rot", "/parameters/species/shape"}) {
    EXPECT_TRUE(link_exists(path, link)) << link;
  }
  // Box edges are stored as a diagonal 3×3 matrix per frame (MDAnalysis turns a vector into a zero box).
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t ds = H5Dopen2(f, "/particles/all/box/edges/value", H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[3] = {0, 0, 0};
  EXPECT_EQ(H5Sget_simple_extent_ndims(space), 3);
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], 1u);
  EXPECT_EQ(dims[1], 3u);
  EXPECT_EQ(dims[2], 3u);
  H5Sclose(space);
  H5Dclose(ds);
  // No `unit` attribute on position/value: MDAnalysis rejects unit strings it does not know.
  EXPECT_EQ(H5Aexists_by_name(f, "/particles/all/position/value", "unit", H5P_DEFAULT), 0);
  H5Fclose(f);
}

TEST_F(H5md, ParticleCountMustStayConstant) {
  Rng rng(1, 2);
  const State a = random_state(rng, 10, Vec3(10, 10, 10), 0, 0);
  const State b = random_state(rng, 11, Vec3(10, 10, 10), 1, 1);
  io::H5mdWriter w(file("t.h5"), header_for(a));
  w.append_frame(a);
  EXPECT_THROW(w.append_frame(b), RuntimeFailure);
  State earlier = a;
  earlier.step = -1;
  EXPECT_THROW(w.append_frame(earlier), RuntimeFailure);
  State bad_species = a;
  bad_species.particles.species[3] = 2;
  EXPECT_THROW(w.append_frame(bad_species), RuntimeFailure);
}

TEST_F(H5md, SpeciesTableTakenFromFirstFrameWhenHeaderHasNone) {
  Rng rng(3, 3);
  const State s = random_state(rng, 5, Vec3(8, 8, 8), 0, 0);
  io::H5mdWriter w(file("t.h5"), io::H5mdHeader{});
  w.append_frame(s);
  w.commit();
  io::H5mdReader r(file("t.h5"));
  expect_same_state(s, r.read_frame(0));
  EXPECT_EQ(r.parameters(), json::object());
}

TEST_F(H5md, ObservablesRoundTrip) {
  Rng rng(9, 9);
  const State s = random_state(rng, 4, Vec3(8, 8, 8), 0, 0);
  const std::string path = file("obs.h5");
  io::H5mdWriter w(path, header_for(s));
  // More rows than frames (as MC runs write) and more rows than the writer buffers at once.
  const std::size_t rows = 10000;
  for (std::size_t i = 0; i < rows; ++i) {
    w.append_observable("acceptance", static_cast<std::int64_t>(i), 0.01 * static_cast<double>(i), 1.0 / (1.0 + i));
    if (i % 1000 == 0) {
      w.append_observable("order", static_cast<std::int64_t>(i), 0.01 * i, std::vector<double>{1.0 * i, -0.5, 1e-300});
    }
    if (i % 2500 == 0) {
      State t = s;
      t.step = static_cast<std::int64_t>(i);
      w.append_frame(t);
    }
  }
  w.set_observable_attribute("acceptance", "units", "1");
  w.set_observable_attribute("acceptance", "definition", "accepted / attempted translation moves");
  w.set_observable_attribute("acceptance", "units", "dimensionless");  // replaces
  // Fewer rows than frames: moved to /anisodyn/observables on commit, still readable.
  w.append_observable("sparse", 42, 4.2, 3.5);
  EXPECT_THROW(w.append_observable("acceptance", 1, 0.0, std::vector<double>{1.0, 2.0}), RuntimeFailure);
  EXPECT_THROW(w.append_observable("order", 1, 0.0, std::vector<double>{1.0}), RuntimeFailure);
  EXPECT_THROW(w.append_observable("bad/name", 1, 0.0, 1.0), RuntimeFailure);
  w.commit();

  EXPECT_TRUE(link_exists(path, "/observables/acceptance"));
  EXPECT_TRUE(link_exists(path, "/observables/order"));  // 10 rows ≥ 4 frames
  EXPECT_FALSE(link_exists(path, "/observables/sparse"));
  EXPECT_TRUE(link_exists(path, "/anisodyn/observables/sparse"));

  io::H5mdReader r(path);
  EXPECT_EQ(r.frame_count(), 4u);
  EXPECT_EQ(r.observable_names(), (std::vector<std::string>{"acceptance", "order", "sparse"}));
  EXPECT_TRUE(r.has_observable("acceptance"));
  EXPECT_FALSE(r.has_observable("energy"));
  const auto acc = r.read_observable("acceptance");
  ASSERT_EQ(acc.rows(), rows);
  EXPECT_EQ(acc.width, 1u);
  for (std::size_t i = 0; i < rows; ++i) {
    ASSERT_EQ(acc.step[i], static_cast<std::int64_t>(i));
    ASSERT_EQ(bits(acc.time[i]), bits(0.01 * static_cast<double>(i)));
    ASSERT_EQ(bits(acc.value[i]), bits(1.0 / (1.0 + i)));
  }
  const auto order = r.read_observable("order");
  ASSERT_EQ(order.rows(), 10u);
  EXPECT_EQ(order.width, 3u);
  EXPECT_EQ(order.value[3 * 4 + 0], 4000.0);
  EXPECT_EQ(order.value[3 * 4 + 2], 1e-300);
  const auto sparse = r.read_observable("sparse");
  ASSERT_EQ(sparse.rows(), 1u);
  EXPECT_EQ(sparse.step[0], 42);
  EXPECT_EQ(sparse.value[0], 3.5);
  EXPECT_EQ(r.observable_attribute("acceptance", "units").value_or(""), "dimensionless");
  EXPECT_EQ(r.observable_attribute("acceptance", "definition").value_or(""), "accepted / attempted translation moves");
  EXPECT_FALSE(r.observable_attribute("acceptance", "nope").has_value());
  const InputError missing = input_error([&] { r.read_observable("energy"); });
  EXPECT_EQ(missing.json_path(), "/observables/energy");
}

TEST_F(H5md, CheckpointFileRoundTrip) {
  Rng rng(77, 3);
  for (int k = 0; k < 5; ++k) rng.uniform();
  State s = random_state(rng, 31, Vec3(12.5, 13.5, 14.5), 123456789012345, 0.1 + 0.2);
  const json engine = {
      {"rng", {{"seed", std::numeric_limits<std::uint64_t>::max()}, {"stream", 3}, {"counter", rng.state().counter},
               {"used", rng.state().used}}},
      {"cycle", 987654321},
      {"dt", {1e-5, 0.1 + 0.2, 5e-324, -0.0, 1.7976931348623157e308}},
      {"accumulated_time", 1.0 / 3.0},
      {"integrator", {{"name", "dmc"}, {"acceptance_window", json::array({0.3, 0.5})}}}};
  const std::string path = file("run.checkpoint.h5");
  io::write_checkpoint_file(path, header_for(s), s, engine);
  EXPECT_FALSE(fs::exists(path + ".partial"));

  auto [state, back] = io::read_checkpoint_file(path);
  expect_same_state(s, state);
  EXPECT_EQ(back, engine);
  EXPECT_EQ(back["rng"]["seed"].get<std::uint64_t>(), std::numeric_limits<std::uint64_t>::max());
  for (std::size_t k = 0; k < engine["dt"].size(); ++k)
    EXPECT_EQ(bits(back["dt"][k].get<double>()), bits(engine["dt"][k].get<double>())) << k;
  // A restored generator continues the same sequence.
  const RngState restored{back["rng"]["seed"].get<std::uint64_t>(), back["rng"]["stream"].get<std::uint64_t>(),
                          back["rng"]["counter"].get<std::uint64_t>(), back["rng"]["used"].get<std::uint32_t>()};
  EXPECT_EQ(restored.counter, rng.state().counter);

  // Overwriting an existing checkpoint replaces it atomically.
  s.step += 1;
  io::write_checkpoint_file(path, header_for(s), s, {{"cycle", 2}});
  auto [state2, back2] = io::read_checkpoint_file(path);
  EXPECT_EQ(state2.step, s.step);
  EXPECT_EQ(back2["cycle"], 2);

  // A trajectory without a checkpoint is not a checkpoint file.
  io::H5mdWriter w(file("traj.h5"), header_for(s));
  w.append_frame(s);
  w.commit();
  const InputError e = input_error([&] { io::read_checkpoint_file(file("traj.h5")); });
  EXPECT_EQ(e.json_path(), "/anisodyn/checkpoint/engine_state");
}

TEST_F(H5md, WriterCheckpointIsReplacedOnEveryCall) {
  Rng rng(4, 4);
  const State s = random_state(rng, 6, Vec3(9, 9, 9), 0, 0);
  io::H5mdWriter w(file("t.h5"), header_for(s));
  w.append_frame(s);
  w.write_checkpoint({{"cycle", 1}, {"note", std::string(5000, 'x')}});
  w.write_checkpoint({{"cycle", 2}});
  w.commit();
  io::H5mdReader r(file("t.h5"));
  ASSERT_TRUE(r.checkpoint().has_value());
  EXPECT_EQ(*r.checkpoint(), json({{"cycle", 2}}));
}

TEST_F(H5md, BadFilesGiveInputErrorsNamingTheHdf5Path) {
  {
    const InputError e = input_error([&] { io::H5mdReader r(file("missing.h5")); });
    EXPECT_EQ(e.file(), file("missing.h5"));
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos);
  }
  {
    std::ofstream(file("text.h5")) << "not hdf5 at all\n";
    const InputError e = input_error([&] { io::H5mdReader r(file("text.h5")); });
    EXPECT_NE(std::string(e.what()).find("not an HDF5 file"), std::string::npos) << e.what();
  }
  Rng rng(8, 8);
  const State s = random_state(rng, 5, Vec3(7, 7, 7), 0, 0);
  auto make = [&](const std::string& name) {
    io::H5mdWriter w(file(name), header_for(s));
    w.append_frame(s);
    w.commit();
    return file(name);
  };
  {
    const std::string p = make("no-orientation.h5");
    delete_link(p, "/particles/all/orientation");
    io::H5mdReader r(p);  // opening works; reading the frame names the missing dataset
    const InputError e = input_error([&] { r.read_frame(0); });
    EXPECT_EQ(e.file(), p);
    EXPECT_EQ(e.json_path(), "/particles/all/orientation/value");
    EXPECT_EQ(std::string(e.what()), p + ": at /particles/all/orientation/value: missing required dataset");
  }
  {
    const std::string p = make("no-h5md.h5");
    delete_link(p, "/h5md");
    EXPECT_EQ(input_error([&] { io::H5mdReader r(p); }).json_path(), "/h5md");
  }
  {
    const std::string p = make("no-species.h5");
    delete_link(p, "/parameters/species/D_rot");
    io::H5mdReader r(p);
    EXPECT_EQ(input_error([&] { r.read_frame(0); }).json_path(), "/parameters/species/D_rot");
  }
  {
    const std::string p = make("no-config.h5");
    delete_link(p, "/parameters/config");
    io::H5mdReader r(p);
    EXPECT_EQ(input_error([&] { r.parameters(); }).json_path(), "/parameters/config");
  }
}

TEST_F(H5md, SuspendedRunResumesFromItsCheckpoint) {
  Rng rng(12, 12);
  std::vector<State> frames;
  for (int f = 0; f < 4; ++f) frames.push_back(random_state(rng, 9, Vec3(10, 11, 12) * (1 + 0.01 * f), 100 * f, 0.5 * f));
  const std::string path = file("resumable.h5");
  {
    io::H5mdWriter w(path, header_for(frames[0]));
    w.set_observable_attribute("energy", "units", "kT");
    for (int f = 0; f < 3; ++f) {
      w.append_frame(frames[f]);
      for (int k = 0; k < 4; ++k) w.append_observable("energy", 100 * f + 25 * k, 0.0, 1.0 * (100 * f + 25 * k));
    }
    w.write_checkpoint({{"step", 100}});  // the run will restart from step 100 …
    w.suspend();                          // … after being interrupted at step 275
    EXPECT_THROW(w.append_frame(frames[3]), RuntimeFailure);
  }
  EXPECT_FALSE(fs::exists(path));
  ASSERT_TRUE(fs::exists(path + ".partial"));

  {
    io::H5mdWriter w = io::H5mdWriter::resume(path, 100);
    EXPECT_EQ(w.frame_count(), 2u);  // frames at steps 0 and 100 are kept
    w.append_observable("energy", 125, 0.0, -1.0);
    w.append_frame(frames[3]);  // replaces the frame at step 200 written before the interruption
    w.write_checkpoint({{"step", 300}});
    w.commit();
  }
  EXPECT_FALSE(fs::exists(path + ".partial"));
  io::H5mdReader r(path);
  ASSERT_EQ(r.frame_count(), 3u);
  expect_same_state(frames[0], r.read_frame(0));
  expect_same_state(frames[1], r.read_frame(1));
  expect_same_state(frames[3], r.read_frame(2));
  const auto e = r.read_observable("energy");
  EXPECT_EQ(e.step, (std::vector<std::int64_t>{0, 25, 50, 75, 100, 125}));
  EXPECT_EQ(e.value.back(), -1.0);
  EXPECT_EQ(r.observable_attribute("energy", "units").value_or(""), "kT");
  EXPECT_EQ((*r.checkpoint())["step"], 300);

  // Nothing to resume → InputError, nothing created.
  const InputError none = input_error([&] { io::H5mdWriter::resume(file("never.h5"), 0); });
  EXPECT_EQ(none.file(), file("never.h5") + ".partial");
  EXPECT_FALSE(fs::exists(file("never.h5.partial")));
}
