#include "ddaslope/contact/broad_phase.hpp"

#include <algorithm>
#include <numeric>

#include "ddaslope/core/block_order.hpp"

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
  // (a, b) order, counted into place by a.
  const std::vector<BlockPair> pairs = sortedByBlock(found, n, [](const BlockPair& p) { return p.a; },
                                                     [](const BlockPair& p, const BlockPair& q) { return p.b < q.b; });
  return pairs;
}

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin) {
  std::vector<int> order;
  return findCandidatePairs(boxes, fixed, margin, order);
}

}  // namespace ddaslope::contact
