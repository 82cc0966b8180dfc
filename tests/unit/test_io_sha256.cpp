// io: SHA-256 against the FIPS 180-2 test vectors and the NIST 1 GiB vector, streamed file hashing
// against GNU coreutils, and provenance records.
#include <gtest/gtest.h>

#include "scratch_dir.hpp"

#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/provenance.hpp"
#include "anisodyn/tool/sha256.hpp"
#include "anisodyn/version.hpp"

using namespace anisodyn;
namespace fs = std::filesystem;

namespace {

class Scratch : public anisodyn::testing_support::ScratchDirTest {
 protected:
  Scratch() : ScratchDirTest("io-sha") {}
};

void write_file(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
}

}  // namespace

TEST(Sha256, Fips180_2Vectors) {
  EXPECT_EQ(tool::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(tool::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(tool::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// NIST's "extremely long message" vector (1 GiB; its bit length needs more than 32 bits), fed in
// 1 MiB pieces as a file would be.
TEST(Sha256, NistGigabyteVectorStreamed) {
  const std::string pattern = "abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno";
  std::string piece;
  while (piece.size() < (1u << 20)) piece += pattern;
  tool::Sha256 h;
  for (int i = 0; i < 1024; ++i) h.update(piece);
  EXPECT_EQ(h.hex_digest(), "50e72a0e26442fe2552dc3938ac58658228c0cbfb1d2ca872ae435266fcd055e");
}

TEST(Sha256, EmptyMessageAndPaddingBoundaries) {
  EXPECT_EQ(tool::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  // 55, 56 and 64 bytes straddle the one-block / two-block padding boundary; incremental hashing in
  // odd pieces must agree with one-shot hashing for every length.
  for (std::size_t len : {55u, 56u, 57u, 63u, 64u, 65u, 119u, 120u, 1000u}) {
    std::string msg;
    for (std::size_t i = 0; i < len; ++i) msg.push_back(static_cast<char>('A' + (i * 7) % 26));
    tool::Sha256 h;
    for (std::size_t pos = 0; pos < len; pos += 13) h.update(std::string_view(msg).substr(pos, 13));
    EXPECT_EQ(h.hex_digest(), tool::sha256_hex(msg)) << "length " << len;
  }
}

TEST_F(Scratch, FileHashEqualsHashOfContents) {
  std::string content;
  for (int i = 0; i < 200000; ++i) content.push_back(static_cast<char>(i * 31 % 251));
  write_file(file("data.bin"), content);
  EXPECT_EQ(tool::sha256_hex_of_file(file("data.bin")), tool::sha256_hex(content));
  write_file(file("abc.txt"), "abc");
  EXPECT_EQ(tool::sha256_hex_of_file(file("abc.txt")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

// A file of several read chunks with a partial last one. Reference digest from GNU coreutils
// `sha256sum` (its own implementation, not OpenSSL's) of 2^24 + 3 bytes 'a'.
TEST_F(Scratch, LargeFileStreamedInChunks) {
  write_file(file("a.bin"), std::string((1u << 24) + 3, 'a'));
  EXPECT_EQ(tool::sha256_hex_of_file(file("a.bin")), "5e7cd5757ad6251fe3d2ec6b40eee62825bf94d13d835891016ef8c85c03ed8a");
}

TEST(Sha256, DigestIsStableAcrossCalls) {
  tool::Sha256 h;
  h.update("abc");
  const std::string first = h.hex_digest();
  EXPECT_EQ(h.hex_digest(), first);
  EXPECT_EQ(first, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_F(Scratch, MissingFileIsAnInputError) {
  try {
    tool::sha256_hex_of_file(file("missing.h5"));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file("missing.h5"));
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos);
  }
}

TEST_F(Scratch, ProvenanceRecordsToolVersionCommandLineAndInputHashes) {
  write_file(file("in.json"), "{\"a\": 1}");
  const std::vector<std::string> argv{"anisodyn-mc", "--config", file("in.json"), "--set", "name=two words"};
  const auto p = tool::make_provenance("anisodyn-mc", argv, {file("in.json")});
  EXPECT_EQ(p["tool"], "anisodyn-mc");
  EXPECT_EQ(p["version"], anisodyn::kVersion);
  EXPECT_EQ(p["git_revision"], anisodyn::kGitRevision);
  EXPECT_EQ(p["command_line"], "anisodyn-mc --config " + file("in.json") + " --set 'name=two words'");
  EXPECT_EQ(p["argv"], argv);
  const std::string t = p["created_utc"];  // YYYY-MM-DDTHH:MM:SSZ
  ASSERT_EQ(t.size(), 20u) << t;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char expected = i == 4 || i == 7 ? '-' : i == 10 ? 'T' : i == 13 || i == 16 ? ':' : i == 19 ? 'Z' : '0';
    if (expected == '0') EXPECT_TRUE(t[i] >= '0' && t[i] <= '9') << t;
    else EXPECT_EQ(t[i], expected) << t;
  }
  EXPECT_TRUE(p["hostname"].is_string());
  ASSERT_EQ(p["inputs"].size(), 1u);
  EXPECT_EQ(p["inputs"][0]["path"], file("in.json"));
  EXPECT_EQ(p["inputs"][0]["sha256"], tool::sha256_hex("{\"a\": 1}"));
  EXPECT_THROW(tool::make_provenance("t", {}, {file("nope")}), InputError);
  EXPECT_EQ(tool::shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(tool::shell_quote(""), "''");
}
