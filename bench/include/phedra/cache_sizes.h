#pragma once
// The processor's cache sizes, as Linux gives them in sysfs: the benchmark sizes
// its memory-bandwidth reference by them, so that a figure means the same on a
// machine with a larger or smaller cache (docs/performance.md).

#include <cstddef>
#include <filesystem>
#include <string>

namespace phedra::bench {

struct CacheSizes {
  std::size_t l2 = 1u << 20;           ///< bytes of the level-2 cache of one core
  std::size_t last_level = 32u << 20;  ///< bytes of the largest (last-level) cache
  bool measured = false;               ///< read from sysfs (else the defaults above)
};

/// "1024K" -> 1048576, "32M" -> 33554432, "512" -> 512; 0 for text that is no size.
std::size_t parse_cache_size(const std::string& text);

/// From DIR/index*/{level,type,size} (data and unified caches; the defaults when
/// DIR holds none).
CacheSizes read_cache_sizes(const std::filesystem::path& dir = "/sys/devices/system/cpu/cpu0/cache");

}  // namespace phedra::bench
