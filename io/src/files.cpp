#include "phedra/files.h"

#include "phedra/errors.h"

#include <random>
#include <sstream>
#include <system_error>

namespace phedra {
namespace fs = std::filesystem;

std::string read_text_file(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IOError(path.string() + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(path.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw IOError(path.string() + ": read error");
  return buffer.str();
}

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  std::error_code ec;
  if (target_.empty()) throw IOError("output path is empty");
  if (fs::is_directory(target_, ec)) throw IOError(target_.string() + ": is a directory");
  const fs::path directory = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, ec)) {
    throw IOError(target_.string() + ": directory " + directory.string() + " does not exist");
  }
  std::random_device device;
  const auto tag = std::to_string(device()) + std::to_string(device());
  temporary_ = directory / ("." + target_.filename().string() + "." + tag + ".tmp");
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw IOError(target_.string() + ": cannot write in " + directory.string() + " (permission denied?)");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) {
    throw IOError(target_.string() + ": write failed (disk full?); nothing was written");
  }
  std::error_code ec;
  fs::rename(temporary_, target_, ec);
  if (ec) throw IOError(target_.string() + ": cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

void write_file_atomically(const fs::path& path, std::string_view content) {
  AtomicFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

void refuse_overwriting_input(const fs::path& output, const fs::path& input) {
  std::error_code ec;
  if (fs::exists(output, ec) && fs::equivalent(output, input, ec)) {
    throw IOError(output.string() + ": is the input file; refusing to overwrite it");
  }
}

}  // namespace phedra
