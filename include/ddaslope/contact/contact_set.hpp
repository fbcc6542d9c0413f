#pragma once
// The persistent contact set: contacts matched by key across steps keep state and history.
#include <vector>

#include "ddaslope/contact/contact.hpp"

namespace ddaslope::contact {

class ContactSet {
 public:
  /// Replaces the contacts by this step's candidates (sorted by key). A candidate whose key
  /// was in contact last step inherits its state, bond and shear anchor; one whose vertex moved
  /// to another edge of the same block inherits state and bond with a fresh anchor.
  /// `bondedIfNew`: whether a candidate with no history starts intact (its joint's bond policy).
  void update(std::vector<ContactCandidate> candidates, const std::vector<int>& jointOfCandidate,
              const std::vector<char>& bondedIfNew);
  bool contains(const ContactKey& key) const;
  /// Callers may change contacts' state, never their keys (the lookup index relies on them).
  std::vector<Contact>& contacts() { return contacts_; }
  const std::vector<Contact>& contacts() const { return contacts_; }

 private:
  void indexBlocks();

  std::vector<Contact> contacts_;  ///< sorted by key
  std::vector<int> firstOfBlock_;  ///< contacts_[firstOfBlock_[b], firstOfBlock_[b + 1]): vertex block b
};

}  // namespace ddaslope::contact
