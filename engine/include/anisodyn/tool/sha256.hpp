#pragma once
// SHA-256 (FIPS 180-4) of files and byte strings, as lowercase hex. Used for provenance records
// (`inputs: [{path, sha256}]`) and by the manifest runner to decide whether an output is current.
// The digest comes from OpenSSL's libcrypto (EVP interface), which picks the CPU's SHA extensions
// when present; this header keeps OpenSSL out of the includes of every client.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace anisodyn::tool {

/// Incremental hasher: update() any number of times, then hex_digest().
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(Sha256&&) noexcept;
  Sha256& operator=(Sha256&&) noexcept;

  void update(const void* data, std::size_t size);
  void update(std::string_view data) { update(data.data(), data.size()); }
  /// Finishes the hash and returns 64 lowercase hex digits (the same digits on every later call);
  /// the hasher must not be updated afterwards.
  std::string hex_digest();

 private:
  struct Context;  // the OpenSSL digest context
  std::unique_ptr<Context> context_;
  std::string digest_;  // set by the first hex_digest()
};

std::string sha256_hex(std::string_view data);

/// Hash of a file's bytes. Missing or unreadable file → InputError(path, "", "cannot open file: …").
std::string sha256_hex_of_file(const std::string& path);

}  // namespace anisodyn::tool
