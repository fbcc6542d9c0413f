// The look-ahead of the panel substitutions (core/prefetch.hpp): which cache lines it asks for,
// recorded instead of prefetched. Only a hint, so what matters is that it covers the run, once,
// neither behind nor too far ahead of the reading, and never outside it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <random>
#include <vector>

#include "ddaslope/core/prefetch.hpp"

using namespace ddaslope;

// Every line of the run is asked for once and none outside it; after each point the reading
// reports, every line up to the distance beyond it has been asked for (no lag), and none more than
// the distance and the rest of a line beyond it (no flood), whichever way the run is read and
// however unevenly the reading advances (a panel's rows, then a wide one's chunks). The run:
// 10 000 bytes from an address 24 bytes into a line (as a panel's entries may start): the 157
// lines that hold bytes 24 … 10 023 of an aligned buffer.
TEST(RunPrefetcher, AsksForEachLineOfTheRunOnceNeitherBehindNorFarAhead) {
  alignas(64) static char buffer[10112];
  const char* begin = buffer + 24;
  const char* end = begin + 10000;
  constexpr std::ptrdiff_t kDistance = 1000;
  const auto lineOf = [&](const char* c) { return (c - buffer) / 64; };
  for (const bool ascending : {true, false}) {
    std::vector<std::ptrdiff_t> asked;
    const char* reached = nullptr;
    const auto record = [&](const void* p) {
      const char* c = static_cast<const char*>(p);
      ASSERT_TRUE(c >= begin && c < end) << "a request outside the run, at byte " << c - buffer;
      ASSERT_LE(ascending ? c - reached : reached - c, kDistance + 63) << "asked for too far ahead";
      asked.push_back(lineOf(c));
    };
    using Prefetcher = BasicRunPrefetcher<decltype(record)>;
    Prefetcher ahead(begin, end, ascending ? Prefetcher::Direction::Ascending : Prefetcher::Direction::Descending,
                     kDistance, record);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> step(1, 700);
    for (std::ptrdiff_t read = 0; read < 10000;) {
      read = std::min<std::ptrdiff_t>(10000, read + step(rng));
      reached = ascending ? begin + read : end - read;
      ahead.reach(reached);
      // The farthest byte that must have been asked for by now, and its line.
      const char* due = ascending ? std::min(reached + kDistance, end) - 1 : std::max(reached - kDistance, begin);
      ASSERT_FALSE(asked.empty());
      const auto [low, high] = std::minmax_element(asked.begin(), asked.end());
      if (ascending)
        ASSERT_GE(*high, lineOf(due)) << "behind the reading at byte " << read;
      else
        ASSERT_LE(*low, lineOf(due)) << "behind the reading at byte " << read;
    }
    std::vector<std::ptrdiff_t> lines = asked;
    std::sort(lines.begin(), lines.end());
    EXPECT_EQ(std::adjacent_find(lines.begin(), lines.end()), lines.end()) << "a line asked for twice";
    ASSERT_EQ(lines.size(), 157u) << (ascending ? "ascending" : "descending");
    EXPECT_EQ(lines.front(), 0);
    EXPECT_EQ(lines.back(), 156);
  }
}

// An empty run asks for nothing, and a position outside the run is taken as its nearest end.
TEST(RunPrefetcher, AsksForNothingOutsideTheRun) {
  alignas(64) static char buffer[256];
  int asked = 0;
  const auto count = [&](const void*) { ++asked; };
  using Prefetcher = BasicRunPrefetcher<decltype(count)>;
  Prefetcher empty(buffer + 10, buffer + 10, Prefetcher::Direction::Ascending, 4096, count);
  empty.reach(buffer + 200);
  EXPECT_EQ(asked, 0);
  Prefetcher down(buffer + 64, buffer + 192, Prefetcher::Direction::Descending, 0, count);
  down.reach(buffer);  // before the run's start: the whole run (lines 1 and 2), nothing more
  EXPECT_EQ(asked, 2);
}
