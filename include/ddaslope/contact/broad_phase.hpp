#pragma once
// Broad phase: a uniform grid over bounding boxes (sweep and prune as a fallback); never an
// all-pairs loop.
#include <vector>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::contact {

struct BlockPair {
  int a = 0;  ///< lower block index
  int b = 0;
  bool operator==(const BlockPair&) const = default;
};

/// Pairs of blocks whose boxes, grown by margin, overlap; pairs of two fixed blocks are
/// skipped. Sorted by (a, b), so the result is deterministic. A uniform grid of cells the size
/// of a typical block finds them; boxes that are not finite fall back to sweepPairs.
/// `sweepOrder`: kept for that fallback between steps.
std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin,
                                          std::vector<int>& sweepOrder);
/// The same pairs by sweep and prune along x. `sweepOrder`: the blocks by the left edge of
/// their box; pass last step's (or an empty vector) and it is brought up to date by insertion,
/// nearly free when blocks move little per step.
std::vector<BlockPair> sweepPairs(const std::vector<geometry::Aabb>& boxes, const std::vector<bool>& fixed,
                                  double margin, std::vector<int>& sweepOrder);
/// The same with a fresh sweep order.
std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin);

}  // namespace ddaslope::contact
