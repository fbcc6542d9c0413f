// Δt control (solver/time_step.hpp): quiet steps grow by 1.5× up to the cap; a grown Δt that
// failed lowers the ceiling of later growth below it, and a run of quiet steps at the ceiling
// raises it again.
#include <gtest/gtest.h>

#include "ddaslope/solver/time_step.hpp"

using ddaslope::solver::StepSizeController;

namespace {

/// Takes quiet steps of what the controller proposes until it proposes the same Δt twice; returns it.
double grownTo(StepSizeController& c) {
  double dt = c.proposal(1e9), last = 0;
  for (int k = 0; k < 100 && dt != last; ++k) {
    last = dt;
    c.acceptedQuiet(dt);
    dt = c.proposal(1e9);
  }
  return dt;
}

}  // namespace

TEST(StepSizeController, QuietStepsGrowToTheCapAndAFailedGrownStepLowersTheCeiling) {
  StepSizeController c(1.0, 0.3);
  EXPECT_EQ(c.growthCap(), 0);
  c.acceptedQuiet(1.0);
  EXPECT_EQ(c.proposal(1e9), 1.0) << "no growth allowed: the nominal Δt";
  c.allowGrowthTo(10.0);
  EXPECT_EQ(c.proposal(1e9), 1.0);
  c.acceptedQuiet(1.0);
  EXPECT_EQ(c.proposal(1e9), 1.5) << "1.5× per quiet step";
  EXPECT_EQ(grownTo(c), 10.0) << "up to the cap";
  // A grown Δt of 6 fails: cut by the cut factor, and growth held below 6 / 1.5 = 4.
  EXPECT_DOUBLE_EQ(c.cut(6.0), 1.8);
  c.accepted(1.8, true);
  EXPECT_EQ(c.proposal(1e9), 1.0) << "after a cut: back to at most the nominal Δt";
  EXPECT_DOUBLE_EQ(grownTo(c), 4.0);
  // 20 quiet steps at the ceiling raise it by 1.5× (grownTo took one at it already).
  for (int k = 0; k < 18; ++k) c.acceptedQuiet(4.0);
  EXPECT_DOUBLE_EQ(c.proposal(1e9), 4.0) << "19 quiet steps at the ceiling";
  c.acceptedQuiet(4.0);
  c.acceptedQuiet(4.0);
  EXPECT_DOUBLE_EQ(c.proposal(1e9), 6.0) << "the 20th raised the ceiling to 6";
  // A failed Δt at or below the nominal one leaves the ceiling alone.
  EXPECT_DOUBLE_EQ(c.cut(1.0), 0.3);
  c.accepted(0.3, true);
  EXPECT_DOUBLE_EQ(grownTo(c), 6.0);
}
