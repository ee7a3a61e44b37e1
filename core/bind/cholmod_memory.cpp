#include "core/bind/cholmod_memory.h"

#include <SuiteSparse_config.h>
#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <utility>
#include <vector>

namespace dfm {
namespace {

constexpr size_t kMinCached = size_t(1) << 20;  // smaller blocks go straight to malloc
constexpr size_t kMaxBlocks = 8;                // per thread
constexpr size_t kHugePage = size_t(2) << 20;
// Blocks smaller than this keep their tails resident: giving them back costs a page fault per page when
// the next, larger face touches them again, and they do not decide the peak memory; the factors of
// large meshes do.
constexpr size_t kMinGivingBack = size_t(16) << 20;
constexpr size_t kPage = 4096;

struct BlockCache {
  std::vector<std::pair<void*, size_t>> blocks;  // free blocks and their usable sizes
  ~BlockCache() { clear(); }
  void clear() {
    for (auto& b : blocks) std::free(b.first);
    blocks.clear();
  }
  // The smallest cached block holding `size` bytes, unless it would waste more than 3/4 of itself.
  void* take(size_t size) {
    size_t best = blocks.size();
    for (size_t k = 0; k < blocks.size(); ++k)
      if (blocks[k].second >= size && blocks[k].second / 4 <= size &&
          (best == blocks.size() || blocks[k].second < blocks[best].second))
        best = k;
    if (best == blocks.size()) {
      // A miss: the blocks too small for it are stale (faces grow); return them before allocating.
      for (size_t k = 0; k < blocks.size();)
        if (blocks[k].second < size) std::free(blocks[k].first), blocks[k] = blocks.back(), blocks.pop_back();
        else ++k;
      return nullptr;
    }
    void* p = blocks[best].first;
    const size_t usable = blocks[best].second;
    blocks[best] = blocks.back();
    blocks.pop_back();
    // Give the pages past what this request uses back to the system (they refault as zeros if a later
    // request needs them): resident memory follows the current face, not the largest one so far.
    const uintptr_t b = (reinterpret_cast<uintptr_t>(p) + size + kPage - 1) & ~(kPage - 1);
    const uintptr_t e = (reinterpret_cast<uintptr_t>(p) + usable) & ~(kPage - 1);
    if (usable >= kMinGivingBack && e > b + kMinCached) madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED);
    return p;
  }
  void put(void* p, size_t usable) {
    if (usable >= kMinGivingBack) {
      // A large free block keeps its address space, not its pages: a cached block that no later face
      // takes would otherwise stay resident; huge pages make the refault of a reused one cheap.
      const uintptr_t b = (reinterpret_cast<uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
      const uintptr_t e = (reinterpret_cast<uintptr_t>(p) + usable) & ~(kPage - 1);
      if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED);
    }
    if (blocks.size() == kMaxBlocks) {  // drop the smallest
      size_t small = 0;
      for (size_t k = 1; k < blocks.size(); ++k)
        if (blocks[k].second < blocks[small].second) small = k;
      if (blocks[small].second >= usable) {
        std::free(p);
        return;
      }
      std::free(blocks[small].first);
      blocks[small] = {p, usable};
      return;
    }
    blocks.emplace_back(p, usable);
  }
};

thread_local BlockCache cache;

void* fresh(size_t size) {
  void* p = std::malloc(size);
  if (p && size >= 2 * kHugePage) {
    // The 2 MB-aligned interior of the block, backed by huge pages when the kernel allows (THP madvise).
    const uintptr_t b = (reinterpret_cast<uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const uintptr_t e = (reinterpret_cast<uintptr_t>(p) + size) & ~(kHugePage - 1);
    if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
  }
  return p;
}

void* cached_malloc(size_t size) {
  if (size >= kMinCached)
    if (void* p = cache.take(size)) return p;
  return size >= kMinCached ? fresh(size) : std::malloc(size);
}

void* cached_calloc(size_t n, size_t s) {
  if (s != 0 && n > SIZE_MAX / s) return nullptr;
  const size_t size = n * s;
  if (size >= kMinCached) {
    if (void* p = cache.take(size)) return std::memset(p, 0, size);
    void* p = fresh(size);
    return p ? std::memset(p, 0, size) : nullptr;
  }
  return std::calloc(n, s);
}

void cached_free(void* p) {
  if (!p) return;
  const size_t usable = malloc_usable_size(p);
  if (usable >= kMinCached) cache.put(p, usable);
  else std::free(p);
}

}  // namespace

void install_cholmod_block_cache() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = cached_malloc;
    SuiteSparse_config.calloc_func = cached_calloc;
    SuiteSparse_config.free_func = cached_free;
    // realloc stays the C library's: cached blocks are ordinary malloc blocks.
  });
}

void release_cholmod_block_cache() { cache.clear(); }

void trim_heap() { malloc_trim(0); }

}  // namespace dfm
