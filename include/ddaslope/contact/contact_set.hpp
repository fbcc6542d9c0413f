#pragma once
// The persistent contact set: contacts matched by key across steps keep state and history.
#include <functional>
#include <vector>

#include "ddaslope/contact/contact.hpp"

namespace ddaslope::contact {

class ContactSet {
 public:
  /// Replaces the contacts by this step's candidates (sorted by key). A candidate whose key
  /// was in contact last step inherits its state, bond and shear anchor; one whose vertex moved
  /// to another edge of the same block inherits state and bond with a fresh anchor.
  /// `bondedIfNew`: whether a candidate with no history starts intact (its joint's bond policy).
  /// With `vertexCount` (a block's number of vertices), an edge-to-edge contact whose measuring
  /// corner changed blocks (the other block's corner at an end of this edge sat on the paired
  /// edge, and is gone) inherits that contact's state and bond with a fresh anchor. With
  /// `fixedBlock`, a vertex that slid from one fixed block's face onto another's (a seam of the
  /// base) inherits its gone contact's state likewise. A vertex that moved onto another edge
  /// of its block and stands clear of it is open; it keeps its bond only if
  /// `bondSurvivesOpening(joint)` (a joint without tensile strength to crack; default: keeps it).
  void update(std::vector<ContactCandidate> candidates, const std::vector<int>& jointOfCandidate,
              const std::vector<char>& bondedIfNew, const std::function<int(int)>& vertexCount = {},
              const std::function<bool(int)>& fixedBlock = {},
              const std::function<bool(int)>& bondSurvivesOpening = {});
  bool contains(const ContactKey& key) const;
  /// Identify the set's keys, and its keys with each contact's paired edge (the edge-to-edge
  /// pairing): an update() that changes them gives a number no set has had before. A copy keeps
  /// them, so a set restored from a copy is told apart from the latest one.
  long keyVersion() const { return keyVersion_; }
  long pairingVersion() const { return pairingVersion_; }
  /// Callers may change contacts' state, never their keys (the lookup index relies on them).
  std::vector<Contact>& contacts() { return contacts_; }
  const std::vector<Contact>& contacts() const { return contacts_; }

 private:
  void indexBlocks();
  /// The same candidate keys in the same order as the last update: each candidate's geometry
  /// goes to the contact it went to then (no sort, no merge); false if the keys differ.
  bool refreshGeometry(const std::vector<ContactCandidate>& candidates);

  std::vector<Contact> contacts_;  ///< sorted by key
  std::vector<int> firstOfBlock_;  ///< contacts_[firstOfBlock_[b], firstOfBlock_[b + 1]): vertex block b
  long keyVersion_ = 0, pairingVersion_ = 0;
  /// The last update's candidate keys, in their order, and where each went in contacts_ (−1: a
  /// duplicate, found from both blocks). They travel with contacts_ when the set is copied.
  std::vector<ContactKey> lastKeys_;
  std::vector<int> placement_;
};

}  // namespace ddaslope::contact
