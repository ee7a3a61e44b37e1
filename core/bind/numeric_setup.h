#pragma once
// Process-wide settings for the weight solver's numerics, set once by each program before it binds
// (deform, deform-editor, the benches, the tests): one BLAS thread, no OpenMP teams, and CHOLMOD's large
// blocks reused (cholmod_memory.h). The solver parallelizes over handles instead; inside each face
// factorization
//  - a threaded BLAS (Debian's libopenblas0-pthread) spawned its own threads while both solver threads
//    ran: oversubscribed, spinning; hand.mesh took 21 s instead of 4.6 s, 16.7 s of it system time;
//  - Debian's CHOLMOD (SuiteSparse 5.12) opens an OpenMP team of a hard-coded 4 threads
//    (num_threads(CHOLMOD_OMP_NUM_THREADS), deaf to OMP_NUM_THREADS) around every supernode. Max active
//    levels 0 makes each team 1 thread;
//  - even a one-thread team costs libgomp a team allocation and a futex wake system call; CHOLMOD opens
//    one per supernode: this library defines GOMP_parallel itself (below), running each region's body
//    once on the calling thread.
// The BLAS and OpenMP functions are looked up at run time (dlsym), so this works with whatever runtime
// is linked and is a no-op without one. Nothing else in the program uses OpenMP or threaded BLAS.
// Without this step a bind gives the same weights, only slower.
namespace dfm {

// Idempotent and thread-safe; call before the first bind.
void setup_numerics();

}  // namespace dfm

// GCC's entry point for `#pragma omp parallel`, defined by this library so that it takes precedence over
// libgomp's in every library of the process (see numeric_setup.cpp). Linked into every program that
// calls setup_numerics().
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);
