// The corpus of bad presets (tests/data/bad, expectations in expected.tsv): every
// command gives the expected message and exit code and writes nothing.

#include "cli.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

struct Expectation {
  std::string file;
  int exit_code;
  std::string message;
};

std::vector<Expectation> expectations() {
  std::ifstream in(std::string(PHEDRA_TEST_DATA_DIR) + "/bad/expected.tsv");
  std::vector<Expectation> list;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Expectation e;
    std::string code;
    std::getline(fields, e.file, '\t');
    std::getline(fields, code, '\t');
    std::getline(fields, e.message);
    e.exit_code = std::stoi(code);
    list.push_back(e);
  }
  return list;
}

}  // namespace

TEST_CASE("at least 40 bad presets, each with its message and exit code, for every command", "[bad]") {
  const std::vector<Expectation> list = expectations();
  CHECK(list.size() >= 40);
  const fs::path out = fs::temp_directory_path() / ("phedra-bad-" + std::to_string(::getpid()));
  fs::create_directories(out);
  for (const Expectation& e : list) {
    CAPTURE(e.file, e.message);
    const std::string preset = std::string(PHEDRA_TEST_DATA_DIR) + "/bad/" + e.file;
    const std::vector<std::vector<std::string>> commands{
        {"info", preset},
        {"check", preset},
        {"sample", preset, "--fraction", "0.5", "-o", (out / "s.json").string()},
        {"generate", preset, "-o", (out / "g.glb").string()},
    };
    for (const auto& args : commands) {
      CAPTURE(args[0]);
      std::ostringstream stdout_text, stderr_text;
      const int code = phedra::cli::run(args, stdout_text, stderr_text);
      CHECK(code == e.exit_code);
      CHECK_THAT(stderr_text.str(), Contains(e.message));
      CHECK_THAT(stderr_text.str(), Contains(preset));
      CHECK(stderr_text.str().find('\n') == stderr_text.str().size() - 1);  // one line
    }
    CHECK(fs::is_empty(out));  // nothing written, not even a temporary file
  }
  fs::remove_all(out);
}
