#include "core/bind/numeric_threads.h"

#include <dlfcn.h>

#include <mutex>

namespace dfm {

namespace {
using SetInt = void (*)(int);
}  // namespace

void single_threaded_numerics() {
  static std::once_flag once;
  static SetInt omp_set_max_active_levels = nullptr;
  std::call_once(once, [] {
    for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads", "bli_thread_set_num_threads"})
      if (void* f = dlsym(RTLD_DEFAULT, name)) reinterpret_cast<SetInt>(f)(1);
    omp_set_max_active_levels = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  });
  if (omp_set_max_active_levels) omp_set_max_active_levels(0);
}

}  // namespace dfm
