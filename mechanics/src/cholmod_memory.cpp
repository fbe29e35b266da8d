#include "cholmod_memory.h"

#ifdef PHEDRA_CHOLMOD
#include <SuiteSparse_config.h>
#include <sys/mman.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#endif

namespace phedra {

#ifdef PHEDRA_CHOLMOD
namespace {

constexpr std::size_t huge_page = std::size_t{1} << 21;

void* huge_malloc(std::size_t size) {
  if (size < huge_page) return std::malloc(size);
  if (size > static_cast<std::size_t>(-1) - huge_page) return nullptr;
  const std::size_t rounded = (size + huge_page - 1) / huge_page * huge_page;
  void* p = std::aligned_alloc(huge_page, rounded);
  if (p != nullptr) madvise(p, rounded, MADV_HUGEPAGE);  // advice only: a refusal changes nothing
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

}  // namespace phedra
