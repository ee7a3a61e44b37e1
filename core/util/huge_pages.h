#pragma once
// Large fresh arrays backed by 2 MB pages. A first touch of a 4 KB page costs a fault, and under a
// virtual machine faults are dear: filling the transition's arrays of millions of tetrahedra cost
// more in faults than in arithmetic (bench_transition). Linux backs a range advised with
// MADV_HUGEPAGE with 2 MB pages where it can (transparent huge pages, "madvise" mode); elsewhere the
// advice does nothing.
#include <cstddef>
#include <vector>

namespace dfm {

// Advises the whole 2 MB pages inside [p, p + bytes), best effort (ignored for small ranges, on
// other systems, and where the kernel refuses). Call it before the memory is first written.
void advise_huge_pages(void* p, std::size_t bytes);

// v with room for n elements, advised before anything is written there.
template <class T, class A>
void reserve_huge(std::vector<T, A>& v, std::size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace dfm
