#pragma once
// A vertex-to-edge contact and the state it carries across steps.
#include <compare>
#include <cstdint>

namespace ddaslope::contact {

enum class ContactState : std::uint8_t { Open = 0, Sliding = 1, Locked = 2 };

/// Identifies a contact across steps (Box2D's feature id): vertex of one block on an edge
/// of another. Edge e of a block runs from vertex e to vertex e+1 (counter-clockwise).
struct ContactKey {
  int vertexBlock = 0;
  int vertex = 0;
  int edgeBlock = 0;
  int edge = 0;
  auto operator<=>(const ContactKey&) const = default;
};

/// What the narrow phase finds at the start of a step.
struct ContactCandidate {
  ContactKey key;
  double gap = 0;     ///< signed distance of the vertex from the edge line, > 0 outside (m)
  double ratio = 0;   ///< position of the vertex's projection along the edge, 0..1
  /// Edge of the vertex block lying against the contact edge (edge-to-edge contact), or −1.
  int pairedEdge = -1;
  double overlap = 0;  ///< overlap length L of that edge-to-edge contact (m), 0 if none
};

struct Contact {
  ContactCandidate geometry;       ///< refreshed every step
  int joint = 0;
  ContactState state = ContactState::Open;
  bool bonded = false;             ///< intact: cohesion and tensile strength still act
  int slideDirection = 0;          ///< +1 / −1 along the edge, while sliding
  double lockRatio = 0;            ///< anchor of the locked shear spring on the edge (0..1)
  double normalOffset = 0;         ///< initial gap taken as touching (m)
  double normalForce = 0;          ///< N from the latest solution (N/m), compression > 0
  double shearForce = 0;           ///< shear spring force from the latest solution (N/m)
  double slipDistance = 0;         ///< slip accumulated while sliding, all steps (m)
  double stepSlip = 0;             ///< slip in the step being solved, while sliding (m)
  /// Largest opening (m) while open with its bond after t = 0, beyond the gap it had at t = 0: a
  /// softening joint without tensile strength loses its bond when it reaches the weakening
  /// distance (contact_law.hpp, separatesWithBond).
  double opening = 0;
  double openingAtStart = 0;  ///< its gap at t = 0 if open then (m): the loading history's, not damage
  /// Fraction of the joint's peak-above-residual strength left (contact/joint_strength.hpp).
  double intact = 1;

  const ContactKey& key() const { return geometry.key; }
  bool closed() const { return state != ContactState::Open; }
};

}  // namespace ddaslope::contact
