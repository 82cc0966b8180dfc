#include "anisodyn/tool/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "anisodyn/core/error.hpp"

namespace anisodyn::tool {
namespace {

std::string directory_of(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return dir.empty() ? std::string(".") : dir;
}

[[noreturn]] void cannot_write(const std::string& path, const std::string& reason) {
  throw InputError(path, "", "cannot write output: " + reason);
}

void fsync_path(const std::string& path, int flags, const std::string& what) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw RuntimeFailure("cannot open " + what + " '" + path + "' for fsync: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  // Some file systems cannot fsync directories (EINVAL); the rename is still atomic there.
  if (rc != 0 && !(err == EINVAL && (flags & O_DIRECTORY)))
    throw RuntimeFailure("fsync of " + what + " '" + path + "' failed: " + std::strerror(err));
}

}  // namespace

void check_output_writable(const std::string& path) {
  if (path.empty()) cannot_write(path, "the output path is empty");
  const std::string dir = directory_of(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    cannot_write(path, "directory '" + dir + "' " +
                           (errno == ENOENT ? std::string("does not exist") : std::strerror(errno)));
  }
  if (!S_ISDIR(st.st_mode)) cannot_write(path, "'" + dir + "' is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    cannot_write(path, "directory '" + dir + "' is not writable (" + std::strerror(errno) + ")");
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    cannot_write(path, "'" + path + "' is a directory");
}

AtomicOutput::AtomicOutput(std::string final_path)
    : final_path_(std::move(final_path)), partial_path_(final_path_ + ".partial") {
  check_output_writable(final_path_);
}

AtomicOutput::AtomicOutput(AtomicOutput&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      partial_path_(std::move(other.partial_path_)),
      committed_(other.committed_),
      keep_partial_(other.keep_partial_),
      active_(other.active_) {
  other.active_ = false;
}

AtomicOutput::~AtomicOutput() {
  if (active_ && !committed_ && !keep_partial_) std::remove(partial_path_.c_str());
}

void AtomicOutput::commit() {
  if (!active_) throw RuntimeFailure("AtomicOutput::commit() on a moved-from object");
  if (committed_) return;
  struct stat st {};
  if (::stat(partial_path_.c_str(), &st) != 0)
    throw RuntimeFailure("cannot commit '" + final_path_ + "': partial file '" + partial_path_ + "' is missing");
  fsync_path(partial_path_, O_RDONLY, "file");
  if (std::rename(partial_path_.c_str(), final_path_.c_str()) != 0)
    throw RuntimeFailure("cannot rename '" + partial_path_ + "' to '" + final_path_ + "': " + std::strerror(errno));
  committed_ = true;
  fsync_path(directory_of(final_path_), O_RDONLY | O_DIRECTORY, "directory");
}

}  // namespace anisodyn::tool
