// SHA-256 through OpenSSL's EVP digest interface (libcrypto), the maintained implementation with
// the x86 SHA extensions and other hardware paths.
#include "anisodyn/tool/sha256.hpp"

#include <openssl/evp.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

#include "anisodyn/core/error.hpp"

namespace anisodyn::tool {
namespace {

// libcrypto reports failures (e.g. no SHA-256 in a FIPS-restricted provider set) by return value.
void require(int ok, const char* what) {
  if (ok != 1) throw RuntimeFailure(std::string("SHA-256 (OpenSSL): ") + what + " failed");
}

std::string lowercase_hex(const unsigned char* bytes, unsigned int size) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(2 * size);
  for (unsigned int i = 0; i < size; ++i) {
    out.push_back(kDigits[bytes[i] >> 4]);
    out.push_back(kDigits[bytes[i] & 0xf]);
  }
  return out;
}

}  // namespace

struct Sha256::Context {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  Context() {
    if (ctx == nullptr) throw RuntimeFailure("SHA-256 (OpenSSL): cannot allocate a digest context");
    require(EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr), "EVP_DigestInit_ex");
  }
  ~Context() { EVP_MD_CTX_free(ctx); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

Sha256::Sha256() : context_(std::make_unique<Context>()) {}
Sha256::~Sha256() = default;
Sha256::Sha256(Sha256&&) noexcept = default;
Sha256& Sha256::operator=(Sha256&&) noexcept = default;

void Sha256::update(const void* data, std::size_t size) {
  require(EVP_DigestUpdate(context_->ctx, data, size), "EVP_DigestUpdate");
}

std::string Sha256::hex_digest() {
  if (digest_.empty()) {
    unsigned char bytes[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    require(EVP_DigestFinal_ex(context_->ctx, bytes, &size), "EVP_DigestFinal_ex");
    digest_ = lowercase_hex(bytes, size);
  }
  return digest_;
}

std::string sha256_hex(std::string_view data) {
  Sha256 hasher;
  hasher.update(data);
  return hasher.hex_digest();
}

std::string sha256_hex_of_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  Sha256 hasher;
  std::vector<char> chunk(1 << 20);  // 1 MiB reads: few system calls per gigabyte
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const std::streamsize got = in.gcount();
    if (got > 0) hasher.update(chunk.data(), static_cast<std::size_t>(got));
  }
  if (in.bad()) throw InputError(path, "", "cannot read file");
  return hasher.hex_digest();
}

}  // namespace anisodyn::tool
