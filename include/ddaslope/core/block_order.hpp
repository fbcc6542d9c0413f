#pragma once
// Sorting per-block items (contacts, block pairs) without a sort of the whole list: items are
// counted into place by their block, then each block's few items are sorted. The result is the
// order `less` gives when it orders by block first, the same as std::sort's for a strict total
// order, at a cost linear in the items plus a few short sorts.
#include <algorithm>
#include <vector>

namespace ddaslope {

/// `items` ordered by blockOf(item) (in [0, blocks)), then by `less` within a block.
template <class T, class BlockOf, class Less>
std::vector<T> sortedByBlock(const std::vector<T>& items, int blocks, BlockOf blockOf, Less less) {
  std::vector<size_t> start(static_cast<size_t>(blocks) + 1, 0);
  for (const T& item : items) ++start[static_cast<size_t>(blockOf(item)) + 1];
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<T> out(items.size());
  std::vector<size_t> next(start.begin(), start.end() - 1);
  for (const T& item : items) out[next[static_cast<size_t>(blockOf(item))]++] = item;
  for (size_t b = 0; b + 1 < start.size(); ++b)
    std::sort(out.begin() + static_cast<long>(start[b]), out.begin() + static_cast<long>(start[b + 1]), less);
  return out;
}

}  // namespace ddaslope
