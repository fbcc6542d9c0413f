#pragma once
// Narrow phase: vertex-to-edge and vertex-to-vertex contacts between two polygons (pure).
#include <cmath>
#include <functional>
#include <vector>

#include "ddaslope/contact/contact.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::contact {

struct NarrowPhaseSettings {
  NarrowPhaseSettings(double searchDistance, double parallelTolerance)
      : searchDistance(searchDistance), sinParallelTolerance(std::sin(parallelTolerance)) {}
  double searchDistance = 0;        ///< vertices farther than this from an edge are ignored (m)
  /// sin of the angle (radians) within which edges count as antiparallel and form an
  /// edge-to-edge contact; taken once here, not per vertex and edge tested.
  double sinParallelTolerance = 0;
};

/// Contacts between blocks a and b (both polygons counter-clockwise). A vertex near a vertex
/// of the other block gives one contact whose entrance edge is the one that best separates
/// the two corners (Shi's angle rule); `known` lets a tie keep the contact of the last step.
void findContacts(int a, const std::vector<Vec2>& pa, int b, const std::vector<Vec2>& pb,
                  const NarrowPhaseSettings& s, const std::function<bool(const ContactKey&)>& known,
                  std::vector<ContactCandidate>& out);

}  // namespace ddaslope::contact
