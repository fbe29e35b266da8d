#include "cholmod_threads.h"

#ifdef PHEDRA_CHOLMOD
#include <dlfcn.h>

#include <initializer_list>
#endif

namespace phedra {

#ifdef PHEDRA_CHOLMOD
namespace {

/// The OpenMP runtime's setter and getter of max-active-levels, found where
/// CHOLMOD loaded it (GNU's libgomp on Debian; LLVM's libomp elsewhere); null
/// when none is loaded. phedra itself is not built with OpenMP.
struct ActiveLevels {
  using Set = void (*)(int);
  using Get = int (*)();
  Set set = nullptr;
  Get get = nullptr;
  ActiveLevels() {
    for (const char* name : {"libgomp.so.1", "libomp.so.5", "libomp.so"}) {
      void* runtime = dlopen(name, RTLD_LAZY | RTLD_NOLOAD);  // only if already loaded
      if (runtime == nullptr) continue;
      set = reinterpret_cast<Set>(dlsym(runtime, "omp_set_max_active_levels"));
      get = reinterpret_cast<Get>(dlsym(runtime, "omp_get_max_active_levels"));
      dlclose(runtime);  // drops the count dlopen added; the library stays loaded
      if (set != nullptr && get != nullptr) return;
      set = nullptr;
      get = nullptr;
    }
  }
};

const ActiveLevels& active_levels() {
  static const ActiveLevels levels;
  return levels;
}

}  // namespace

OpenMPRegionsSerial::OpenMPRegionsSerial() {
  const ActiveLevels& levels = active_levels();
  if (levels.set == nullptr) return;
  previous_ = levels.get();
  levels.set(0);  // no region is active: each runs on the thread that meets it
}

OpenMPRegionsSerial::~OpenMPRegionsSerial() {
  if (previous_ >= 0) active_levels().set(previous_);
}
#else
OpenMPRegionsSerial::OpenMPRegionsSerial() = default;
OpenMPRegionsSerial::~OpenMPRegionsSerial() = default;
#endif

}  // namespace phedra
