#pragma once
// A fresh scratch directory per test, under $ANISODYN_TEST_TMP (set by ctest) or the system
// temporary directory, removed afterwards.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace anisodyn::testing_support {

class ScratchDirTest : public ::testing::Test {
 protected:
  explicit ScratchDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    namespace fs = std::filesystem;
    const char* base = std::getenv("ANISODYN_TEST_TMP");
    const std::string root = base && *base ? base : fs::temp_directory_path().string();
    fs::create_directories(root);
    std::string templ = root + "/" + prefix_ + "-XXXXXX";
    ASSERT_NE(mkdtemp(templ.data()), nullptr);
    dir_ = templ;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string file(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;

 private:
  std::string prefix_;
};

}  // namespace anisodyn::testing_support
