#pragma once
// Reuse of CHOLMOD's large blocks. Every face factorization allocates the factor's values afresh and
// frees them after the solve; glibc maps such blocks anew each time, and the page faults of first touch
// plus CHOLMOD's zeroing are a large share of the bounded solve on big meshes. Blocks of 1 MB and more
// that CHOLMOD frees are kept per thread and handed back to the next request they fit, so a face reuses
// the last face's memory. Big fresh blocks are advised for transparent huge pages (fewer faults).
// Blocks of 16 MB and more keep only their address space while cached (their pages are given back), so
// stale blocks cost no memory; smaller ones stay resident (refaulting them would cost more than they hold).

namespace dfm {

// Points SuiteSparse's allocator at the cache. Idempotent; call before any CHOLMOD use.
void install_cholmod_block_cache();
// Frees the calling thread's cached blocks (a thread's cache is also freed when the thread ends).
void release_cholmod_block_cache();

// Hands the C library's free heap memory back to the system (malloc_trim): on large binds, what one
// stage freed, before the next one peaks. Small meshes would pay more in page faults than they save.
void trim_heap();

// Releases the calling thread's cached blocks when it goes out of scope, however the scope is left.
struct CholmodBlockCacheScope {
  CholmodBlockCacheScope() = default;
  CholmodBlockCacheScope(const CholmodBlockCacheScope&) = delete;
  CholmodBlockCacheScope& operator=(const CholmodBlockCacheScope&) = delete;
  ~CholmodBlockCacheScope() { release_cholmod_block_cache(); }
};

}  // namespace dfm
