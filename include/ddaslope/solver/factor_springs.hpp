#pragma once
// Keeps the Cholesky factor of a large system in step with contact state changes. Within a step
// K changes only by contact springs switched on or off (a contact closes or opens, sticks or
// slips), each a rank-one term k v vᵀ. Passing those terms to the factor as an update/downdate
// costs far less than a new factorisation of a large system, and leaves the factor exact up to
// the geometric drift that conjugate gradients already absorb between steps. This class records
// which springs the factor holds and turns a new set into the columns √k·v to add and remove.
#include <vector>

#include "ddaslope/assembly/contact_terms.hpp"
#include "ddaslope/contact/contact.hpp"
#include "ddaslope/solver/sparse_cholesky.hpp"

namespace ddaslope::solver {


/// The springs one contact puts into K.
struct ContactSprings {
  contact::ContactKey key;
  int blockI = -1, blockJ = -1;  ///< active block indices of its vertex and edge block (−1: fixed)
  double normalK = 0, shearK = 0;  ///< 0: that spring is off
  Vec12 normal = Vec12::Zero(), shear = Vec12::Zero();
};

class FactorSprings {
 public:
  /// The factor was just computed from a K holding these springs (any order).
  void reset(std::vector<ContactSprings> inFactor);
  /// Forget the record (no factor, or one whose springs are unknown).
  void invalidate() { valid_ = false; }
  bool valid() const { return valid_; }
  /// The columns that take the factor from the recorded springs to `now` (a spring switched on:
  /// added; off: removed with the vector it was added with), over `dof` unknowns per block;
  /// `now` becomes the record. A spring that stays on keeps its recorded vector: its geometric
  /// drift is left to conjugate gradients.
  void changes(std::vector<ContactSprings> now, int dof, std::vector<SparseCholesky::Column>& added,
               std::vector<SparseCholesky::Column>& removed);
  /// True if `contacts` (in key order) switch on exactly the recorded springs: a closed contact
  /// its normal spring, a locked one its shear spring too. changes() would then find nothing, so
  /// a step whose states stand need not build its springs, which costs a pass over every contact.
  bool holdsSame(const std::vector<contact::Contact>& contacts) const;

 private:
  /// What holdsSame compares of a recorded contact, kept apart from its vectors: the check runs
  /// every iteration and would otherwise read 230-byte records for 20 of their bytes.
  struct Switched {
    contact::ContactKey key;
    bool normal = false, shear = false;
  };
  void record(std::vector<ContactSprings> springs);

  std::vector<ContactSprings> recorded_;  ///< sorted by key
  std::vector<Switched> switched_;        ///< recorded_'s keys and springs switched on, in its order
  bool valid_ = false;
};

}  // namespace ddaslope::solver
