#include "phedra/cache_sizes.h"

#include <algorithm>
#include <cctype>
#include <fstream>

namespace phedra::bench {

std::size_t parse_cache_size(const std::string& text) {
  std::size_t k = 0, value = 0;
  while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
  const std::size_t digits = k;
  for (; k < text.size() && std::isdigit(static_cast<unsigned char>(text[k])); ++k) {
    value = 10 * value + static_cast<std::size_t>(text[k] - '0');
  }
  if (k == digits) return 0;
  const char unit = k < text.size() ? static_cast<char>(std::toupper(static_cast<unsigned char>(text[k]))) : '\0';
  if (unit == 'K') return value << 10;
  if (unit == 'M') return value << 20;
  if (unit == 'G') return value << 30;
  return unit == '\0' || std::isspace(static_cast<unsigned char>(unit)) ? value : 0;
}

CacheSizes read_cache_sizes(const std::filesystem::path& dir) {
  CacheSizes sizes;
  std::size_t l2 = 0, largest = 0;
  int deepest = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().filename().string().rfind("index", 0) != 0) continue;
    auto read = [&](const char* name) {
      std::ifstream in(entry.path() / name);
      std::string text;
      std::getline(in, text);
      return text;
    };
    const std::string type = read("type");
    if (type != "Data" && type != "Unified") continue;
    const int level = std::atoi(read("level").c_str());
    const std::size_t size = parse_cache_size(read("size"));
    if (size == 0) continue;
    if (level == 2) l2 = std::max(l2, size);
    if (level > deepest || (level == deepest && size > largest)) {
      deepest = level;
      largest = size;
    }
  }
  if (l2 > 0 && largest > 0) {
    sizes.l2 = l2;
    sizes.last_level = largest;
    sizes.measured = true;
  }
  return sizes;
}

}  // namespace phedra::bench
