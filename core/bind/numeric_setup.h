#pragma once
// Process-wide settings for the weight solver's numerics. They change the whole process, so no core
// function applies them behind a caller's back: each program that binds (deform, deform-editor,
// bench_bind, bench_fast, the tests through tests/numerics_setup.cpp) takes two explicit steps,
//   DFM_RUN_OPENMP_REGIONS_SERIALLY()   once at file scope beside main, and
//   dfm::setup_numerics();              first thing in main.
// The solver parallelizes over handles instead; inside each factorization
//  - a threaded BLAS (Debian's libopenblas0-pthread) spawns its own threads while both solver threads
//    run: oversubscribed and spinning, several times slower, most of it system time;
//  - Debian's CHOLMOD (SuiteSparse 5.12) opens an OpenMP team of a hard-coded 4 threads
//    (num_threads(CHOLMOD_OMP_NUM_THREADS), deaf to OMP_NUM_THREADS) around every supernode. Max active
//    levels 0 makes each team 1 thread;
//  - even a one-thread team costs libgomp a team allocation and a futex wake system call per
//    supernode: the program defines GOMP_parallel itself (the macro below), running each region's body
//    once on the calling thread.
// The BLAS and OpenMP functions are looked up at run time (dlsym), so this works with whatever runtime
// is linked and is a no-op without one. Nothing else in the programs uses OpenMP or threaded BLAS.
// Without these steps a bind gives the same weights, only slower.
namespace dfm {

// One BLAS thread, OpenMP max active levels 0, CHOLMOD's large blocks reused (cholmod_memory.h).
// Idempotent and thread-safe; call before the first bind.
void setup_numerics();

}  // namespace dfm

// GCC's entry point for `#pragma omp parallel`. A definition in the executable takes precedence over
// libgomp's for every library of the process; it runs the region's body once on the calling thread,
// which is what a one-thread team does (work-sharing loops, barriers and critical sections inside are
// orphaned constructs that libgomp runs correctly outside a team). Declared here, defined only by a
// program that expands DFM_RUN_OPENMP_REGIONS_SERIALLY().
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);

// Defines GOMP_parallel (above) in the program that expands it: once, at file scope, in its main file.
#define DFM_RUN_OPENMP_REGIONS_SERIALLY()                                                 \
  extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned, unsigned) { fn(data); }
