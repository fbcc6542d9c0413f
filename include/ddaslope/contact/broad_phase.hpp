#pragma once
// Broad phase: sweep and prune over bounding boxes; never an all-pairs loop.
#include <vector>

#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::contact {

struct BlockPair {
  int a = 0;  ///< lower block index
  int b = 0;
  bool operator==(const BlockPair&) const = default;
};

/// Pairs of blocks whose boxes, grown by margin, overlap; pairs of two fixed blocks are
/// skipped. Sorted by (a, b), so the result is deterministic.
/// `sweepOrder`: the blocks by the left edge of their box; pass last step's (or an empty vector)
/// and it is brought up to date by insertion, nearly free when blocks move little per step.
std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin,
                                          std::vector<int>& sweepOrder);
/// The same with a fresh sweep order.
std::vector<BlockPair> findCandidatePairs(const std::vector<geometry::Aabb>& boxes,
                                          const std::vector<bool>& fixed, double margin);

}  // namespace ddaslope::contact
