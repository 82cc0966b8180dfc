// io: atomic outputs — nothing at the final path before commit, partial files removed on failure,
// unusable output paths refused before anything is created.
#include <gtest/gtest.h>

#include "scratch_dir.hpp"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/atomic_file.hpp"
#include "anisodyn/io/h5md.hpp"

using namespace anisodyn;
namespace fs = std::filesystem;

namespace {

class Atomic : public anisodyn::testing_support::ScratchDirTest {
 protected:
  Atomic() : ScratchDirTest("io-atomic") {}
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_ + "/readonly", fs::perms::owner_all, ec);  // so the directory can be removed
    ScratchDirTest::TearDown();
  }
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator())); }
};

State small_state() {
  State s;
  Species a;
  a.name = "A";
  a.shape = Shape::sphere(1.0);
  s.species = {a};
  s.box = Box(Vec3(5, 5, 5));
  s.particles.add(0, Vec3(1, 2, 3), Quat::Identity(), 0);
  return s;
}

}  // namespace

TEST_F(Atomic, NothingAtFinalPathBeforeCommit) {
  const std::string out = file("result.csv");
  {
    tool::AtomicOutput a(out);
    EXPECT_EQ(a.partial_path(), out + ".partial");
    EXPECT_EQ(entries(), 0u);  // the constructor creates nothing
    std::ofstream(a.partial_path()) << "x,y\n1,2\n";
    EXPECT_FALSE(fs::exists(out));
    a.commit();
    EXPECT_TRUE(a.committed());
  }
  EXPECT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y");
}

TEST_F(Atomic, PartialRemovedWithoutCommit) {
  const std::string out = file("result.csv");
  {
    tool::AtomicOutput a(out);
    std::ofstream(a.partial_path()) << "half";
    EXPECT_TRUE(fs::exists(a.partial_path()));
  }
  EXPECT_FALSE(fs::exists(out + ".partial"));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Atomic, CommitReplacesAnOlderFile) {
  const std::string out = file("r.txt");
  std::ofstream(out) << "old";
  tool::AtomicOutput a(out);
  std::ofstream(a.partial_path()) << "new";
  a.commit();
  std::ifstream in(out);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "new");
}

TEST_F(Atomic, CommitWithoutPartialFileIsARuntimeFailure) {
  tool::AtomicOutput a(file("never-written.h5"));
  EXPECT_THROW(a.commit(), RuntimeFailure);
}

TEST_F(Atomic, MissingDirectoryIsAnInputErrorAndCreatesNothing) {
  const std::string out = file("no/such/dir/out.h5");
  try {
    tool::AtomicOutput a(out);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), out);
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cannot write output: directory '" + file("no/such/dir") + "' does not exist"), std::string::npos) << msg;
  }
  EXPECT_THROW(tool::check_output_writable(out), InputError);
  EXPECT_EQ(entries(), 0u);
}

TEST_F(Atomic, DirectoryAsOutputOrParentIsAFile) {
  fs::create_directory(file("sub"));
  EXPECT_THROW(tool::check_output_writable(file("sub")), InputError);
  std::ofstream(file("plain")) << "x";
  EXPECT_THROW(tool::check_output_writable(file("plain/out.h5")), InputError);
  EXPECT_THROW(tool::check_output_writable(""), InputError);
  EXPECT_NO_THROW(tool::check_output_writable(file("fine.h5")));
  EXPECT_FALSE(fs::exists(file("fine.h5")));
}

TEST_F(Atomic, UnwritableDirectoryIsAnInputError) {
  const std::string ro = file("readonly");
  fs::create_directory(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  if (::access(ro.c_str(), W_OK) == 0) GTEST_SKIP() << "running with privileges that ignore directory permissions";
  try {
    io::H5mdWriter w(ro + "/traj.h5", io::H5mdHeader{});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not writable"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(ro));
}

TEST_F(Atomic, H5mdWriterPublishesOnlyOnCommit) {
  const std::string out = file("traj.h5");
  {
    io::H5mdWriter w(out, io::H5mdHeader{});
    w.append_frame(small_state());
    w.append_observable("energy", 0, 0.0, 1.0);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(fs::exists(out + ".partial"));
    w.commit();
    EXPECT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".partial"));
    EXPECT_THROW(w.append_frame(small_state()), RuntimeFailure);  // nothing after commit
  }
  EXPECT_EQ(io::H5mdReader(out).frame_count(), 1u);
}

TEST_F(Atomic, H5mdWriterDestroyedWithoutCommitLeavesNothing) {
  const std::string out = file("traj.h5");
  try {
    io::H5mdWriter w(out, io::H5mdHeader{});
    w.append_frame(small_state());
    w.write_checkpoint({{"step", 0}});
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  EXPECT_EQ(entries(), 0u);
}

TEST_F(Atomic, H5mdWriterToMissingDirectoryCreatesNothing) {
  EXPECT_THROW(io::H5mdWriter(file("missing/traj.h5"), io::H5mdHeader{}), InputError);
  EXPECT_THROW(io::write_checkpoint_file(file("missing/cp.h5"), io::H5mdHeader{}, small_state(), {}), InputError);
  EXPECT_EQ(entries(), 0u);
}
