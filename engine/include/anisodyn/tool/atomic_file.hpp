#pragma once
// Atomic outputs (architecture §3): a stage writes `<output>.partial`, fsyncs it, and renames it to
// `<output>`, so an output file either is complete or does not exist. A writer that is destroyed
// without commit() (exception, interruption) removes its partial file.
#include <string>

namespace anisodyn::tool {

/// Throws InputError(path, "", "cannot write output: <reason>") unless `path` can be created:
/// its directory exists, is a directory and is writable, and `path` itself is not a directory.
/// Creates nothing. Tools call it before a long computation so that bad output paths fail at once.
void check_output_writable(const std::string& path);

class AtomicOutput {
 public:
  /// Checks the target as check_output_writable() does; creates nothing.
  explicit AtomicOutput(std::string final_path);
  AtomicOutput(AtomicOutput&& other) noexcept;
  AtomicOutput& operator=(AtomicOutput&&) = delete;
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  /// Removes the partial file unless commit() succeeded.
  ~AtomicOutput();

  const std::string& final_path() const { return final_path_; }
  /// final_path + ".partial": where the caller writes (and closes) the file before commit().
  const std::string& partial_path() const { return partial_path_; }
  bool committed() const { return committed_; }

  /// fsyncs the partial file, renames it to the final path and fsyncs the directory.
  /// Throws RuntimeFailure if the partial file is missing or a system call fails.
  void commit();

  /// Leaves the partial file on disk when this object is destroyed (an interrupted run that will
  /// be resumed, see H5mdWriter::suspend()).
  void keep_partial(bool keep = true) { keep_partial_ = keep; }

 private:
  std::string final_path_, partial_path_;
  bool committed_ = false;
  bool keep_partial_ = false;
  bool active_ = true;  // false once moved from
};

}  // namespace anisodyn::tool
