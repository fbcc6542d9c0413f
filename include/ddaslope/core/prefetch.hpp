#pragma once
// Asking the memory system for data before it is read: for passes over arrays larger than the
// cache whose order the hardware prefetcher does not follow (a factor's panels read back to front,
// an edge-to-edge pair's second half further on in the contacts). Only a hint: it never changes
// a result, and compilers without the builtin simply skip it.
#include <cstddef>

namespace ddaslope {

/// Asks for the cache line holding p.
inline void prefetchLine(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

/// Asks for every cache line of the `bytes` bytes from p, the last partial line included, without
/// waiting for any (the processor still holds back when too many misses are outstanding).
inline void prefetchBytes(const void* p, std::ptrdiff_t bytes) {
  constexpr std::ptrdiff_t kLine = 64;
  const char* c = static_cast<const char*>(p);
  for (std::ptrdiff_t o = 0; o < bytes; o += kLine) prefetchLine(c + o);
  if (bytes > 0) prefetchLine(c + (bytes - 1));
}

}  // namespace ddaslope
