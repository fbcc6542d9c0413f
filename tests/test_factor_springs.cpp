// The record of the springs a factor holds (solver/factor_springs.hpp): the changes it reports
// are exactly the springs switched on and off, by definition, and a spring that stays on keeps
// the vector the factor was given.
#include <gtest/gtest.h>

#include <cmath>

#include "ddaslope/solver/factor_springs.hpp"

using namespace ddaslope;
using solver::ContactSprings;

namespace {
ContactSprings spring(int vertex, double normalK, double shearK, double value) {
  ContactSprings s;
  s.key = {0, vertex, 1, 0};
  s.blockI = 0;
  s.blockJ = 1;
  s.normalK = normalK;
  s.shearK = shearK;
  s.normal = Vec12::Constant(value);
  s.shear = Vec12::Constant(-value);
  return s;
}
}  // namespace

TEST(FactorSprings, ReportsSpringsSwitchedOnAndOff) {
  solver::FactorSprings f;
  EXPECT_FALSE(f.valid());
  // In the factor: contact 1 locked (normal and shear), contact 2 sliding (normal only).
  f.reset({spring(2, 4, 0, 2), spring(1, 4, 1, 1)});
  ASSERT_TRUE(f.valid());
  // Now: 1 slides (its shear spring goes), 2 has left, 3 is new and locked. Contact 1's normal
  // vector has drifted (3 instead of 1): it stays on, so nothing is reported for it.
  std::vector<solver::SparseCholesky::Column> added, removed;
  f.changes({spring(3, 4, 1, 5), spring(1, 4, 0, 3)}, 6, added, removed);
  ASSERT_EQ(added.size(), 2u);    // contact 3: normal and shear
  ASSERT_EQ(removed.size(), 2u);  // contact 1: shear; contact 2: normal
  // Columns are √k·v over six unknowns of each of the two free blocks.
  for (const auto& c : added) EXPECT_EQ(c.count, 12);
  EXPECT_DOUBLE_EQ(removed[0].values[0], -1.0 * std::sqrt(1.0));  // contact 1's recorded shear
  EXPECT_DOUBLE_EQ(removed[1].values[0], 2.0 * std::sqrt(4.0));   // contact 2's normal
  // Contact 1 sticks again: its shear spring comes back with the new vector; its normal spring
  // still holds the recorded vector (1), so removing it later takes out what the factor holds.
  f.changes({spring(3, 4, 1, 5), spring(1, 4, 1, 7)}, 6, added, removed);
  ASSERT_EQ(added.size(), 1u);
  EXPECT_DOUBLE_EQ(added[0].values[0], -7.0);
  EXPECT_TRUE(removed.empty());
  f.changes({spring(3, 4, 1, 5)}, 6, added, removed);
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_DOUBLE_EQ(removed[0].values[0], 1.0 * std::sqrt(4.0));
  // A fixed block's unknowns are left out (rigid blocks: three per block).
  ContactSprings onBase = spring(4, 9, 0, 1);
  onBase.blockJ = -1;
  f.changes({onBase}, 3, added, removed);
  ASSERT_EQ(added.size(), 1u);
  EXPECT_EQ(added[0].count, 3);
  EXPECT_DOUBLE_EQ(added[0].values[0], 3.0);
}

namespace {
contact::Contact contactAt(int vertex, contact::ContactState state) {
  contact::Contact c;
  c.geometry.key = {0, vertex, 1, 0};
  c.state = state;
  return c;
}
}  // namespace

// holdsSame is changes() finding nothing, without building the springs: a closed contact holds
// its normal spring, a locked one its shear spring too (by definition, as Simulation builds them).
TEST(FactorSprings, HoldsSameExactlyWhenNothingSwitches) {
  using contact::ContactState;
  solver::FactorSprings f;
  f.reset({spring(1, 4, 1, 1), spring(2, 4, 0, 2)});
  const contact::Contact open3 = contactAt(3, ContactState::Open);
  EXPECT_TRUE(f.holdsSame({contactAt(1, ContactState::Locked), contactAt(2, ContactState::Sliding), open3}));
  EXPECT_FALSE(f.holdsSame({contactAt(1, ContactState::Sliding), contactAt(2, ContactState::Sliding)}));
  EXPECT_FALSE(f.holdsSame({contactAt(1, ContactState::Locked), contactAt(2, ContactState::Locked)}));
  EXPECT_FALSE(f.holdsSame({contactAt(1, ContactState::Locked)}));  // contact 2 opened
  EXPECT_FALSE(f.holdsSame({contactAt(1, ContactState::Locked), contactAt(2, ContactState::Sliding),
                            contactAt(3, ContactState::Sliding)}));  // contact 3 closed
  // Each verdict agrees with what changes() reports.
  std::vector<solver::SparseCholesky::Column> added, removed;
  f.changes({spring(1, 4, 1, 1), spring(2, 4, 0, 2)}, 6, added, removed);
  EXPECT_TRUE(added.empty() && removed.empty());
  f.changes({spring(1, 4, 0, 1), spring(2, 4, 0, 2)}, 6, added, removed);
  EXPECT_EQ(removed.size(), 1u);
}
