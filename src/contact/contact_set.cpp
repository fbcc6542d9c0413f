#include "ddaslope/contact/contact_set.hpp"

#include <algorithm>
#include <atomic>

#include "ddaslope/core/block_order.hpp"

namespace ddaslope::contact {

static bool keyLess(const Contact& c, const ContactKey& k) { return c.key() < k; }

/// A number no version has had.
static long newVersion() {
  static std::atomic<long> versions{0};
  return ++versions;
}

bool ContactSet::contains(const ContactKey& key) const {
  // Search only the contacts of the key's vertex block: a few, not all of them.
  const size_t b = static_cast<size_t>(key.vertexBlock);
  if (key.vertexBlock < 0 || b + 1 >= firstOfBlock_.size()) return false;
  const auto end = contacts_.begin() + firstOfBlock_[b + 1];
  const auto it = std::lower_bound(contacts_.begin() + firstOfBlock_[b], end, key, keyLess);
  return it != end && it->key() == key;
}

void ContactSet::indexBlocks() {
  const int blocks = contacts_.empty() ? 0 : contacts_.back().key().vertexBlock + 1;
  firstOfBlock_.assign(static_cast<size_t>(blocks) + 1, 0);
  for (const Contact& c : contacts_) ++firstOfBlock_[static_cast<size_t>(c.key().vertexBlock) + 1];
  for (size_t b = 1; b < firstOfBlock_.size(); ++b) firstOfBlock_[b] += firstOfBlock_[b - 1];
}

bool ContactSet::refreshGeometry(const std::vector<ContactCandidate>& candidates) {
  if (candidates.size() != lastKeys_.size()) return false;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (!(candidates[i].key == lastKeys_[i])) return false;
  bool samePairing = true;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (placement_[i] < 0) continue;
    ContactCandidate& g = contacts_[static_cast<size_t>(placement_[i])].geometry;
    samePairing = samePairing && g.pairedEdge == candidates[i].pairedEdge;
    g = candidates[i];
  }
  if (!samePairing) pairingVersion_ = newVersion();
  return true;
}

void ContactSet::update(std::vector<ContactCandidate> candidates, const std::vector<int>& jointOfCandidate,
                        const std::vector<char>& bondedIfNew, const std::function<int(int)>& vertexCount,
                        const std::function<bool(int)>& fixedBlock,
                        const std::function<bool(int)>& bondSurvivesOpening) {
  // A scene at rest finds the same contacts step after step: the merge below would give each its
  // candidate's geometry and nothing else (the keys of this set are last update's, unchanged).
  if (refreshGeometry(candidates)) return;
  // Keys sorted with their candidate's index next to them, not reached through it. Candidates
  // of equal key (one contact found from both blocks) are equal, so the order among them
  // does not matter.
  struct Entry {
    ContactKey key;
    size_t idx;
  };
  int blocks = 0;
  for (const ContactCandidate& c : candidates) blocks = std::max(blocks, c.key.vertexBlock + 1);
  std::vector<Entry> order(candidates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = {candidates[i].key, i};
  order = sortedByBlock(order, blocks, [](const Entry& e) { return e.key.vertexBlock; },
                        [](const Entry& x, const Entry& y) { return x.key < y.key; });
  std::vector<Contact> next;
  next.reserve(candidates.size());
  placement_.assign(candidates.size(), -1);
  lastKeys_.resize(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) lastKeys_[i] = candidates[i].key;
  // Both lists are sorted by key: last step's contacts are matched by one forward walk.
  auto previous = contacts_.begin();
  std::vector<ContactKey> handedOver;  // last step's contacts a new one took its state from
  for (const auto& [key, idx] : order) {
    const ContactCandidate& cand = candidates[idx];
    if (!next.empty() && next.back().key() == cand.key) continue;  // found from both sides
    placement_[idx] = static_cast<int>(next.size());
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
    const auto inherit = [&](const Contact& from) {
      c.state = from.state;
      c.bonded = from.bonded;
      c.slipDistance = from.slipDistance;
      c.opening = from.opening;
      c.openingAtStart = from.openingAtStart;
      c.intact = from.intact;
      c.slideDirection = from.slideDirection;
      c.normalForce = from.normalForce;
      c.lockRatio = cand.ratio;
    };
    bool inherited = false;
    {
      // The vertex may have slid onto another edge of the same block: carry its state over.
      const ContactKey prefix{cand.key.vertexBlock, cand.key.vertex, cand.key.edgeBlock, -1};
      for (auto it = std::lower_bound(contacts_.begin(), contacts_.end(), prefix, keyLess);
           it != contacts_.end() && it->key().vertexBlock == prefix.vertexBlock &&
           it->key().vertex == prefix.vertex && it->key().edgeBlock == prefix.edgeBlock;
           ++it) {
        if (!it->closed()) continue;
        inherit(*it);
        // Past a convex bend the vertex stands clear of the next face: it keeps the joint's
        // history but is open until it touches. Closed, its spring would pull it down across the
        // gap, and the iteration would pass that pull round the block's other contacts until
        // the states cycled and froze a lock (docs/contact-model.md).
        // Opened so, it keeps its bond as a contact pulled open by the iteration would.
        if (cand.gap > 0) {
          c.state = ContactState::Open, c.slideDirection = 0, c.normalForce = 0;
          if (bondSurvivesOpening && !bondSurvivesOpening(c.joint)) c.bonded = false;
        }
        inherited = true;
        break;
      }
    }
    if (!inherited && fixedBlock && fixedBlock(cand.key.edgeBlock)) {
      // The vertex is crossing a seam of the base, from one fixed block's face onto the next one's:
      // near the seam it touches both, and the contact on the next face is the same sliding
      // contact going on (in the new joint's bond), not a fresh one closing locked.
      const ContactKey prefix{cand.key.vertexBlock, cand.key.vertex, -1, -1};
      for (auto it = std::lower_bound(contacts_.begin(), contacts_.end(), prefix, keyLess);
           it != contacts_.end() && it->key().vertexBlock == prefix.vertexBlock && it->key().vertex == prefix.vertex;
           ++it) {
        if (!it->closed() || it->key().edgeBlock == cand.key.edgeBlock || !fixedBlock(it->key().edgeBlock)) continue;
        if (std::find(handedOver.begin(), handedOver.end(), it->key()) != handedOver.end()) continue;
        const bool bond = c.bonded;
        inherit(*it);
        if (c.joint != it->joint) c.bonded = bond && it->bonded;
        handedOver.push_back(it->key());
        inherited = true;
        break;
      }
    }
    if (!inherited && vertexCount && cand.pairedEdge >= 0) {
      // Two edges lying against each other, and the corner that measured their contact has
      // changed sides: last step the edge block's corner at an end of this edge sat on the edge
      // this vertex starts or ends (the paired edge); now this vertex sits on the edge. It is the
      // same contact seen from the other block (a slide leaving the corner it started on, once
      // the corners are a search distance apart): it goes on in its state, or it would close
      // afresh, locked, and stop a sliding block in one step.
      // The two edges run in opposite directions (both counter-clockwise): the vertex starting
      // the paired edge lies at the end of this edge, the one ending it at its start. Only the
      // edge block's corner there can have measured this end of the overlap.
      const int corner = cand.key.vertex == cand.pairedEdge ? (cand.key.edge + 1) % vertexCount(cand.key.edgeBlock)
                                                             : cand.key.edge;
      const ContactKey swapped{cand.key.edgeBlock, corner, cand.key.vertexBlock, cand.pairedEdge};
      const auto it = std::lower_bound(contacts_.begin(), contacts_.end(), swapped, keyLess);
      // Not if that contact goes on too (it keeps its own state), nor twice.
      const auto still = std::lower_bound(order.begin(), order.end(), swapped,
                                          [](const Entry& e, const ContactKey& k) { return e.key < k; });
      const bool goesOn = still != order.end() && still->key == swapped;
      if (it != contacts_.end() && it->key() == swapped && it->closed() && !goesOn &&
          std::find(handedOver.begin(), handedOver.end(), swapped) == handedOver.end()) {
        inherit(*it);
        c.normalOffset = it->normalOffset;  // the same gap across the same joint
        handedOver.push_back(swapped);
      }
    }
    next.push_back(c);
  }
  contacts_ = std::move(next);
  indexBlocks();
  keyVersion_ = newVersion();
  pairingVersion_ = newVersion();
}

}  // namespace ddaslope::contact
