#pragma once
// SHA-256 (FIPS 180-4) of files and byte strings, as lowercase hex. Used for provenance records
// (`inputs: [{path, sha256}]`) and by the manifest runner to decide whether an output is current.
#include <cstdint>
#include <string>
#include <string_view>

namespace anisodyn::io {

/// Incremental hasher: update() any number of times, then hex_digest() once.
class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t size);
  void update(std::string_view data) { update(data.data(), data.size()); }
  /// Finishes the hash and returns 64 lowercase hex digits; the hasher must not be updated afterwards.
  std::string hex_digest();

 private:
  void compress(const unsigned char* block);
  std::uint32_t h_[8];
  unsigned char buffer_[64];
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
  bool finished_ = false;
};

std::string sha256_hex(std::string_view data);

/// Hash of a file's bytes. Missing or unreadable file → InputError(path, "", "cannot open file: …").
std::string sha256_hex_of_file(const std::string& path);

}  // namespace anisodyn::io
