#pragma once
// One BLAS thread and no OpenMP teams for the whole process. The weight solver runs one QP per core and
// each QP factorizes many small faces; inside every factorization
//  - a threaded BLAS (Debian's libopenblas0-pthread) spawned its own threads while both solver threads
//    ran: oversubscribed, spinning; hand.mesh took 21 s instead of 4.6 s, 16.7 s of it system time;
//  - Debian's CHOLMOD (SuiteSparse 5.12) opens an OpenMP team of a hard-coded 4 threads
//    (num_threads(CHOLMOD_OMP_NUM_THREADS), deaf to OMP_NUM_THREADS) around every supernode: 1.35M
//    futex calls and ~3 s of system time per hand solve. Max active levels 0 makes each team 1 thread.
//  - even a one-thread team costs libgomp a team allocation and a futex wake system call; CHOLMOD opens
//    one per supernode (200K system calls per hand.mesh bind): this library defines GOMP_parallel
//    itself (below), running each region's body once on the calling thread.
// The solver parallelizes over handles instead. The functions are looked up at run time (dlsym), so
// this works with whatever BLAS / OpenMP runtime is linked and is a no-op without one. Nothing else in
// the program uses OpenMP or threaded BLAS.
namespace dfm {

// Call on every thread that runs CHOLMOD (the OpenMP setting is per thread; the BLAS one is global).
void single_threaded_numerics();

}  // namespace dfm

// GCC's entry point for `#pragma omp parallel`, defined by this library so that it takes precedence over
// libgomp's in every library of the process (see numeric_threads.cpp).
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);
