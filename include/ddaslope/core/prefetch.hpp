#pragma once
// Asking the memory system for data before it is read: for passes over arrays larger than the
// cache that the hardware prefetcher does not follow well (a factor's panels, an edge-to-edge
// pair's second half further on in the contacts). Only a hint: it never changes a result, and
// compilers without the builtin simply skip it.
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace ddaslope {

/// The cache line's size assumed throughout (x86-64 and most ARM cores).
constexpr std::size_t kCacheLine = 64;

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
  constexpr auto kLine = static_cast<std::ptrdiff_t>(kCacheLine);
  const char* c = static_cast<const char*>(p);
  for (std::ptrdiff_t o = 0; o < bytes; o += kLine) prefetchLine(c + o);
  if (bytes > 0) prefetchLine(c + (bytes - 1));
}

/// Asks for one cache line (the default of BasicRunPrefetcher; a test records instead).
struct LineRequest {
  void operator()(const void* p) const { prefetchLine(p); }
};

/// Keeps the lines of an array read as one run, from its start to its end or back, asked for a
/// fixed distance ahead of the reading, however unevenly the reads advance (a factor's panels
/// hold from a hundred bytes to megabytes each): where a whole panel was asked for at once, more
/// lines than the processor keeps in flight, the look-ahead is about the distance beyond each
/// point `reach` is told of. How often the reader tells it sets how steady it is.
template <class Ask = LineRequest>
class BasicRunPrefetcher {
 public:
  enum class Direction { Ascending, Descending };
  BasicRunPrefetcher(const void* begin, const void* end, Direction direction, std::size_t distance, Ask ask = {})
      : begin_(address(begin)),
        end_(address(end)),
        ascending_(direction == Direction::Ascending),
        distance_(distance),
        ask_(ask) {
    // Lines are numbered by address / kLine; `next_` is the next line to ask for.
    if (end_ > begin_) next_ = ascending_ ? line(begin_) : line(end_ - 1);
    last_ = ascending_ ? (end_ > begin_ ? line(end_ - 1) : 0) : line(begin_);
  }
  /// The reading has reached `position` (the far end of what it reads next, in the run's
  /// direction): every line of the run up to `distance` bytes beyond it is asked for, each once.
  void reach(const void* position) {
    if (end_ <= begin_) return;
    const std::uintptr_t p = std::clamp(address(position), begin_, end_);
    if (ascending_) {
      const std::uintptr_t target = end_ - p > distance_ ? p + distance_ : end_;  // the first byte not asked for
      for (const std::intptr_t upTo = line(target - 1); next_ <= upTo && next_ <= last_; ++next_) ask_(lineAt(next_));
    } else {
      const std::uintptr_t target = p - begin_ > distance_ ? p - distance_ : begin_;  // the last byte asked for
      for (const std::intptr_t downTo = line(target); next_ >= downTo && next_ >= last_; --next_) ask_(lineAt(next_));
    }
  }

 private:
  static constexpr std::uintptr_t kLine = kCacheLine;
  // Addresses as integers: the look-ahead steps by whole lines, which may begin before the run.
  static std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }
  static std::intptr_t line(std::uintptr_t a) { return static_cast<std::intptr_t>(a / kLine); }
  /// An address in line l within the run (its first byte, or the run's first).
  const void* lineAt(std::intptr_t l) const {
    const std::uintptr_t a = static_cast<std::uintptr_t>(l) * kLine;
    return reinterpret_cast<const void*>(a > begin_ ? a : begin_);
  }
  std::uintptr_t begin_, end_;
  bool ascending_;
  std::uintptr_t distance_;
  Ask ask_;
  std::intptr_t next_ = 0;  ///< the next line to ask for
  std::intptr_t last_ = 0;  ///< the run's last line in its direction
};
using RunPrefetcher = BasicRunPrefetcher<>;

}  // namespace ddaslope
