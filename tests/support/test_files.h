#pragma once
// Where the tests find their files (the shipped presets, tests/data), and
// reading a JSON file: shared by the test files.

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace phedra::test {

inline const std::string data = PHEDRA_TEST_DATA_DIR;
inline const std::string presets = PHEDRA_PRESETS_DIR;

/// The JSON document of a file (a parse error fails the test that reads it).
inline nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// A scratch directory for one test file's outputs (phedra-NAME-PID under the
/// system's temporary directory), removed with everything in it at the end.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("phedra-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

}  // namespace phedra::test
