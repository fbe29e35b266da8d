#pragma once
// Where the tests find their files (the shipped presets, tests/data), and
// reading a JSON file: shared by the test files.

#include <nlohmann/json.hpp>

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

}  // namespace phedra::test
