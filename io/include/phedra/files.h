#pragma once
// Whole files: reading one as text, and output files that appear whole or not
// at all (AtomicFile: content goes to a temporary file beside the target and is
// renamed over it on commit(); a failure, or a destructor without commit,
// removes the temporary file).

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace phedra {
/// Reads a whole file (IOError naming the path when it cannot).
std::string read_text_file(const std::filesystem::path& path);

class AtomicFile {
 public:
  /// Opens a temporary file in the target's directory. IOError when the
  /// directory does not exist, the target is a directory, or it is not writable.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  /// Flushes, checks for write errors (a full disk), and renames into place.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// write_file_atomically(path, text): AtomicFile in one call.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// IOError when `output` names the same file as `input` (never overwrite an input).
void refuse_overwriting_input(const std::filesystem::path& output, const std::filesystem::path& input);

}  // namespace phedra
