#pragma once
// FNV-1a, 64 bit: the one hash for change detection and file checksums (offset basis
// 14695981039346656037, prime 1099511628211). Not for security.
#include <cstddef>
#include <cstdint>
#include <string>

namespace dfm {

inline constexpr std::uint64_t kFnv1aBasis = 14695981039346656037ull;

// Continues hash h over `bytes` bytes at p (start with kFnv1aBasis).
inline std::uint64_t fnv1a(std::uint64_t h, const void* p, std::size_t bytes) {
  const unsigned char* b = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

inline std::uint64_t fnv1a(const std::string& s) { return fnv1a(kFnv1aBasis, s.data(), s.size()); }

}  // namespace dfm
