#include "ddaslope/contact/broad_phase.hpp"

#include <algorithm>
#include <numeric>

namespace ddaslope::contact {

std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin) {
  const int n = static_cast<int>(boxes.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return boxes[i].lo.x() < boxes[j].lo.x() || (boxes[i].lo.x() == boxes[j].lo.x() && i < j);
  });
  std::vector<BlockPair> pairs;
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    const double reach = boxes[i].hi.x() + margin;
    for (int m = k + 1; m < n; ++m) {
      const int j = order[m];
      if (boxes[j].lo.x() - margin > reach) break;
      if (fixed[i] && fixed[j]) continue;
      if (boxes[i].lo.y() - margin > boxes[j].hi.y() + margin) continue;
      if (boxes[j].lo.y() - margin > boxes[i].hi.y() + margin) continue;
      pairs.push_back({std::min(i, j), std::max(i, j)});
    }
  }
  std::sort(pairs.begin(), pairs.end(),
            [](const BlockPair& p, const BlockPair& q) { return p.a < q.a || (p.a == q.a && p.b < q.b); });
  return pairs;
}

}  // namespace ddaslope::contact
