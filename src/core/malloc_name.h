// Which allocator serves this process's malloc: reported beside timings (benchmarks, timing.json),
// since it changes time and nothing else.
#pragma once

#include <dlfcn.h>

#include <string>

namespace phdslam {

/// "tcmalloc", "jemalloc" or "mimalloc" when that allocator is loaded (linked or preloaded),
/// otherwise "system".
inline std::string MallocName() {
  if (dlsym(RTLD_DEFAULT, "tc_version") != nullptr) return "tcmalloc";
  if (dlsym(RTLD_DEFAULT, "mallctl") != nullptr) return "jemalloc";
  if (dlsym(RTLD_DEFAULT, "mi_version") != nullptr) return "mimalloc";
  return "system";
}

}  // namespace phdslam
