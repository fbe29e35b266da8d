#include "cholmod_memory.h"

#ifdef PHEDRA_CHOLMOD
#include <SuiteSparse_config.h>
#include <sys/mman.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#endif

#include <fstream>
#include <string>
#include <system_error>

namespace phedra {

#ifdef PHEDRA_CHOLMOD
namespace {

constexpr std::size_t huge_page = std::size_t{1} << 21;

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14 (older kernels refuse it: the pages then fault as they are touched)
#endif

/// Huge pages unless the guest reports its free memory to the host (cholmod_memory.h).
bool huge_pages_pay() {
  static const bool pay = [] {
    if (const char* choice = std::getenv("PHEDRA_HUGE_PAGES"); choice != nullptr && *choice != '\0') {
      return std::string(choice) != "0";
    }
    return !reports_free_pages("/sys/bus/virtio/devices");
  }();
  return pay;
}

void* huge_malloc(std::size_t size) {
  if (size < huge_page) return std::malloc(size);
  if (size > static_cast<std::size_t>(-1) - huge_page) return nullptr;
  const std::size_t rounded = (size + huge_page - 1) / huge_page * huge_page;
  void* p = std::aligned_alloc(huge_page, rounded);
  // Advice only: a refusal changes nothing.
  if (p != nullptr) madvise(p, rounded, huge_pages_pay() ? MADV_HUGEPAGE : MADV_POPULATE_WRITE);
  return p;
}

void* huge_calloc(std::size_t count, std::size_t size) {
  if (size != 0 && count > static_cast<std::size_t>(-1) / size) return nullptr;
  const std::size_t bytes = count * size;
  if (bytes < huge_page) return std::calloc(count, size);
  void* p = huge_malloc(bytes);
  if (p != nullptr) std::memset(p, 0, bytes);
  return p;
}

}  // namespace

void cholmod_on_huge_pages() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = huge_malloc;
    SuiteSparse_config.calloc_func = huge_calloc;
    SuiteSparse_config.realloc_func = std::realloc;  // glibc reallocates aligned blocks too
    SuiteSparse_config.free_func = std::free;
  });
}
#else
void cholmod_on_huge_pages() {}
#endif

bool reports_free_pages(const std::filesystem::path& virtio_devices) {
  constexpr std::size_t free_page_reporting = 5;  // VIRTIO_BALLOON_F_REPORTING
  std::error_code error;
  for (const auto& device : std::filesystem::directory_iterator(virtio_devices, error)) {
    std::string id, features;
    std::ifstream(device.path() / "device") >> id;
    if (id != "0x0005") continue;  // not a balloon
    std::ifstream(device.path() / "features") >> features;  // one character a feature bit, bit 0 first
    if (features.size() > free_page_reporting && features[free_page_reporting] == '1') return true;
  }
  return false;  // no such directory (not a virtio guest), or no balloon that reports
}

}  // namespace phedra
