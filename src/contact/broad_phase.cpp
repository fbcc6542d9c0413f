#include "ddaslope/contact/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace ddaslope::contact {

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin,
                                          std::vector<int>& order) {
  const int n = static_cast<int>(boxes.size());
  // A strict total order (left edge, then index), so any sorting method gives the same sweep.
  const auto before = [&](int i, int j) {
    return boxes[i].lo.x() < boxes[j].lo.x() || (boxes[i].lo.x() == boxes[j].lo.x() && i < j);
  };
  if (static_cast<int>(order.size()) != n) {
    order.resize(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), before);
  } else {
    for (int k = 1; k < n; ++k) {  // insertion: last step's order is nearly right
      const int i = order[static_cast<size_t>(k)];
      int m = k;
      while (m > 0 && before(i, order[static_cast<size_t>(m - 1)])) {
        order[static_cast<size_t>(m)] = order[static_cast<size_t>(m - 1)];
        --m;
      }
      order[static_cast<size_t>(m)] = i;
    }
  }
  std::vector<BlockPair> found;
  for (int k = 0; k < n; ++k) {
    const int i = order[static_cast<size_t>(k)];
    const double reach = boxes[i].hi.x() + margin;
    for (int m = k + 1; m < n; ++m) {
      const int j = order[static_cast<size_t>(m)];
      if (boxes[j].lo.x() - margin > reach) break;
      if (fixed[i] && fixed[j]) continue;
      if (boxes[i].lo.y() - margin > boxes[j].hi.y() + margin) continue;
      if (boxes[j].lo.y() - margin > boxes[i].hi.y() + margin) continue;
      found.push_back({std::min(i, j), std::max(i, j)});
    }
  }
  // (a, b) order: counted into place by a, then each block's few partners sorted by b, instead
  // of a sort of the whole list.
  std::vector<int> start(static_cast<size_t>(n) + 1, 0);
  for (const BlockPair& p : found) ++start[static_cast<size_t>(p.a) + 1];
  for (size_t a = 1; a < start.size(); ++a) start[a] += start[a - 1];
  std::vector<BlockPair> pairs(found.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (const BlockPair& p : found) pairs[static_cast<size_t>(next[static_cast<size_t>(p.a)]++)] = p;
  for (int a = 0; a < n; ++a)
    std::sort(pairs.begin() + start[static_cast<size_t>(a)], pairs.begin() + start[static_cast<size_t>(a) + 1],
              [](const BlockPair& p, const BlockPair& q) { return p.b < q.b; });
  return pairs;
}

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin) {
  std::vector<int> order;
  return findCandidatePairs(boxes, fixed, margin, order);
}

}  // namespace ddaslope::contact
