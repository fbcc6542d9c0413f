#pragma once
// Narrow phase: vertex-to-edge and vertex-to-vertex contacts between two polygons (pure).
#include <functional>
#include <vector>

#include "ddaslope/contact/contact.hpp"
#include "ddaslope/core/types.hpp"

namespace ddaslope::contact {

struct NarrowPhaseSettings {
  double searchDistance = 0;       ///< vertices farther than this from an edge are ignored (m)
  double parallelTolerance = 0;    ///< radians: edges this close to antiparallel form an edge-to-edge contact
};

/// Contacts between blocks a and b (both polygons counter-clockwise). A vertex near a vertex
/// of the other block gives one contact whose entrance edge is the one that best separates
/// the two corners (Shi's angle rule); `known` lets a tie keep the contact of the last step.
void findContacts(int a, const std::vector<Vec2>& pa, int b, const std::vector<Vec2>& pb,
                  const NarrowPhaseSettings& s, const std::function<bool(const ContactKey&)>& known,
                  std::vector<ContactCandidate>& out);

}  // namespace ddaslope::contact
