#include "core/bind/numeric_setup.h"

#include <dlfcn.h>

#include <mutex>

#include "core/bind/cholmod_memory.h"

namespace dfm {

namespace {
using SetInt = void (*)(int);
}  // namespace

void setup_numerics() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const char* name : {"openblas_set_num_threads", "goto_set_num_threads", "bli_thread_set_num_threads"})
      if (void* f = dlsym(RTLD_DEFAULT, name)) reinterpret_cast<SetInt>(f)(1);
    // libgomp keeps max-active-levels process-wide.
    if (void* f = dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")) reinterpret_cast<SetInt>(f)(0);
    install_cholmod_block_cache();
  });
}

}  // namespace dfm
