#include "ddaslope/contact/contact_set.hpp"

#include <algorithm>

namespace ddaslope::contact {

static bool keyLess(const Contact& c, const ContactKey& k) { return c.key() < k; }

bool ContactSet::contains(const ContactKey& key) const {
  const auto it = std::lower_bound(contacts_.begin(), contacts_.end(), key, keyLess);
  return it != contacts_.end() && it->key() == key;
}

void ContactSet::update(std::vector<ContactCandidate> candidates, const std::vector<int>& jointOfCandidate,
                        const std::vector<char>& bondedIfNew) {
  std::vector<size_t> order(candidates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return candidates[a].key < candidates[b].key; });
  std::vector<Contact> next;
  next.reserve(candidates.size());
  // Both lists are sorted by key: last step's contacts are matched by one forward walk.
  auto previous = contacts_.begin();
  for (size_t idx : order) {
    const ContactCandidate& cand = candidates[idx];
    if (!next.empty() && next.back().key() == cand.key) continue;  // found from both sides
    while (previous != contacts_.end() && previous->key() < cand.key) ++previous;
    if (previous != contacts_.end() && previous->key() == cand.key) {
      next.push_back(*previous);
      next.back().geometry = cand;
      continue;
    }
    Contact c;
    c.geometry = cand;
    c.joint = jointOfCandidate[idx];
    c.bonded = bondedIfNew[idx];
    {
      // The vertex may have slid onto another edge of the same block: carry its state over.
      const ContactKey prefix{cand.key.vertexBlock, cand.key.vertex, cand.key.edgeBlock, -1};
      for (auto it = std::lower_bound(contacts_.begin(), contacts_.end(), prefix, keyLess);
           it != contacts_.end() && it->key().vertexBlock == prefix.vertexBlock &&
           it->key().vertex == prefix.vertex && it->key().edgeBlock == prefix.edgeBlock;
           ++it) {
        if (!it->closed()) continue;
        c.state = it->state;
        c.bonded = it->bonded;
        c.slipDistance = it->slipDistance;
        c.intact = it->intact;
        c.slideDirection = it->slideDirection;
        c.normalForce = it->normalForce;
        c.lockRatio = cand.ratio;
        break;
      }
    }
    next.push_back(c);
  }
  contacts_ = std::move(next);
}

}  // namespace ddaslope::contact
