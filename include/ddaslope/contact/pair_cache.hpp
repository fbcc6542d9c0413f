#pragma once
// Reuses each block pair's narrow-phase decisions between steps while its two blocks have moved
// less than the search certified (narrow_phase.hpp, SearchMargin): which vertex meets which edge
// is then known, and only the contacts' gap, ratio and pairing are computed again, on the
// present geometry, exactly as a new search would compute them. In a scene mostly at rest
// (a slope before failure, the quiet wall) most pairs are reused; a pair whose blocks moved is
// searched anew.
//
// A block's motion is measured against an anchor, a copy of its vertices: the largest distance of
// a vertex from its anchored position (its drift) bounds, with the drift at the pair's search,
// how far each vertex has gone since that search.
#include <cstdint>
#include <functional>
#include <vector>

#include "ddaslope/contact/broad_phase.hpp"
#include "ddaslope/contact/narrow_phase.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::contact {

class PairCache {
 public:
  using Polygons = std::vector<const std::vector<Vec2>*>;
  using Known = std::function<bool(const ContactKey&)>;

  /// Starts a detection over `pairs` (sorted by (a, b), as the broad phase gives them).
  /// `knownVersion` identifies the keys `known` answers from (ContactSet::keyVersion): the reuse
  /// assumes they are the keys the last detection made, and forgets everything otherwise.
  void prepare(const Polygons& blocks, const std::vector<BlockPair>& pairs, const NarrowPhaseSettings& s,
               long knownVersion);
  /// Pair k's contacts, appended to `out` in the order findContacts gives them: reused or searched
  /// anew. Calls for distinct k may run on different threads. `boxes`: the blocks' bounding
  /// boxes, if the caller has them.
  void find(int k, const Polygons& blocks, const NarrowPhaseSettings& s, const Known& known,
            std::vector<ContactCandidate>& out, const std::vector<geometry::Aabb>* boxes = nullptr);
  /// Ends the detection: `knownVersion` identifies the keys it produced.
  void finish(long knownVersion);
  /// Pairs reused and searched in the last detection.
  long reused() const { return reused_; }
  long searched() const { return searched_; }
  /// Of the pairs searched, those searched without a certificate (Entry::reuses).
  long uncertified() const { return waited_; }

 private:
  struct Anchor {
    std::vector<Vec2> vertices;
    double drift = 0;  ///< largest distance of a vertex from its anchored position (m)
    long epoch = 0;    ///< changes with every new anchor
  };
  /// One contact found, packed: which block holds the vertex (bit 31: b), vertex, edge.
  using Found = std::uint32_t;
  static constexpr int kMaxFound = 8;
  struct Entry {
    BlockPair pair;
    long epochA = 0, epochB = 0;
    double driftA = 0, driftB = 0;  ///< each block's drift when the pair was searched
    double slack = 0;               ///< 0: not reusable
    int count = 0;
    Found found[kMaxFound];
    /// Certifying a search costs about as much as the search. A pair whose blocks keep moving
    /// uses no certificate before it lapses, so such a pair is searched without one for a while:
    /// after a certificate its blocks moved beyond unused, 1, then 3, 7 and 15 searches
    /// (2^level − 1), then certified again, on its blocks anchored anew; a certificate used once
    /// starts the count afresh. (One lost only to an anchor renewed for another pair counts for
    /// nothing.)
    bool certified = false;  ///< this search was certified
    int reuses = 0;          ///< detections that reused this search's contacts
    std::uint8_t level = 0;  ///< certificates in a row that lapsed unused (at most kMaxLevel)
    std::uint8_t wait = 0;   ///< searches still to make without certifying
  };
  static constexpr int kMaxLevel = 4;
  bool holds(const Entry& e) const;

  std::vector<Anchor> anchors_;
  std::vector<Entry> entries_;  ///< the last detection's, sorted by pair
  std::vector<Entry> next_;     ///< this detection's, one per pair
  std::vector<int> previous_;   ///< pair k's entry in entries_ if it is reused, or −1
  std::vector<int> prior_;      ///< pair k's entry in entries_, reused or not, or −1
  std::vector<char> movedAway_;  ///< pair k's blocks moved beyond its last certificate
  long expectedVersion_ = -1;
  double searchDistance_ = -1, sinParallelTolerance_ = -1;
  long reused_ = 0, searched_ = 0, waited_ = 0;
};

}  // namespace ddaslope::contact
