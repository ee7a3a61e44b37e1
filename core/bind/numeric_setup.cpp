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

// Every `#pragma omp parallel` region compiled by GCC enters libgomp through GOMP_parallel. Even a
// one-thread team (max active levels 0, above) allocates a team and ends with a futex wake system call,
// and Debian's CHOLMOD opens one around every supernode: ~200K system calls per hand.mesh bind, 12-15%
// of its CPU time (measured with strace -c and perf). This definition, in the executable, takes
// precedence over libgomp's for every library in the process: it runs the region's body once on the
// calling thread, which is what a one-thread team does. Work-sharing loops, barriers and critical sections
// inside the body are orphaned constructs that libgomp runs correctly outside any team. Nothing in this
// program wants OpenMP threads (numeric_setup.h).
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned /*num_threads*/, unsigned /*flags*/) {
  fn(data);
}
