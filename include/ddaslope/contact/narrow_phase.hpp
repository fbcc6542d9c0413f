#pragma once
// Narrow phase: vertex-to-edge and vertex-to-vertex contacts between two polygons (pure).
#include <array>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "ddaslope/contact/contact.hpp"
#include "ddaslope/core/types.hpp"
#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::contact {

struct NarrowPhaseSettings {
  NarrowPhaseSettings(double searchDistance, double parallelTolerance)
      : searchDistance(searchDistance), sinParallelTolerance(std::sin(parallelTolerance)) {}
  double searchDistance = 0;        ///< vertices farther than this from an edge are ignored (m)
  /// sin of the angle (radians) within which edges count as antiparallel and form an
  /// edge-to-edge contact; taken once here, not per vertex and edge tested.
  double sinParallelTolerance = 0;
  /// Per block, per vertex, flags of the fixed blocks' seams (a base of several fixed blocks):
  /// kFlatCorner, a vertex where another fixed block continues the face flush, which is no corner
  /// for a third block (its corner passes over it onto the next face instead of meeting it); and
  /// kInternalEdge, the edge from the vertex lies against another fixed block's, inside the base,
  /// and is no face for a third block. Null, or empty for a block: none.
  const std::vector<std::vector<char>>* flatCorners = nullptr;
};

constexpr char kFlatCorner = 1, kInternalEdge = 2;

/// What a search certifies about its own decisions (the reuse of contact/pair_cache.hpp): while
/// no vertex of either block has moved by `slack` (m) or more from where it was, a new search
/// takes every decision this one took (which vertex meets which edge, which entrance), provided
/// `known` gives the same answers to the questions recorded here. Only the continuous geometry
/// of the contacts found (gap, ratio, overlap, paired edge) then needs computing again.
///
/// Each comparison of a quantity q with a threshold t records |q − t| / r, where r bounds how fast
/// q changes per metre of vertex motion δ: 2 for a coordinate, or a distance between points and
/// segments of the two blocks (each end moves by δ); 4/ℓ for a unit edge direction of an edge at
/// least ℓ long (|Δ(v/|v|)| ≤ 2|Δv|/|v|, |Δv| ≤ 2δ), taken as 5/ℓ for the second-order terms,
/// with the slack capped at 1 % of the shortest edge so that they stay small. A decision that is
/// an exact tie has slack 0: no certificate.
struct SearchMargin {
  double slack = INFINITY;
  /// The questions the search put to `known`, with the answers.
  std::array<std::pair<ContactKey, bool>, 16> asked{};
  int askedCount = 0;
  bool tooManyQuestions = false;
};

/// Contacts between blocks a and b (both polygons counter-clockwise). A vertex near a vertex
/// of the other block gives one contact whose entrance edge is the one that best separates
/// the two corners (Shi's angle rule); `known` lets a tie keep the contact of the last step.
/// With `margin`, the search also certifies its decisions (SearchMargin). `boxes`: the two
/// polygons' bounding boxes (geometry::boundingBox), when the caller has them already.
void findContacts(int a, const std::vector<Vec2>& pa, int b, const std::vector<Vec2>& pb,
                  const NarrowPhaseSettings& s, const std::function<bool(const ContactKey&)>& known,
                  std::vector<ContactCandidate>& out, SearchMargin* margin = nullptr,
                  const std::array<geometry::Aabb, 2>* boxes = nullptr);

/// The candidate of vertex v of block a on edge e of block b (one of the contacts findContacts
/// reports): its gap, ratio and edge-to-edge pairing on the present geometry.
ContactCandidate contactCandidate(int a, const std::vector<Vec2>& pa, int v, int b, const std::vector<Vec2>& pb,
                                  int e, const NarrowPhaseSettings& s);

}  // namespace ddaslope::contact
