// The open-close cycle detector (solver/state_cycle.hpp). Its rule, from its definition: a period
// P in [2, 6] is reported once the last 3·P records each equal the one P before, so first at
// record (prefix + 4·P); constant states and longer periods are never reported.
#include <gtest/gtest.h>

#include <vector>

#include "ddaslope/solver/state_cycle.hpp"

using namespace ddaslope;
using contact::Contact;
using contact::ContactState;

namespace {

/// Two contacts; `pattern` picks one of four joint states per iteration.
std::vector<Contact> statesOf(int pattern) {
  std::vector<Contact> c(2);
  c[0].state = pattern & 1 ? ContactState::Locked : ContactState::Open;
  c[1].state = pattern & 2 ? ContactState::Sliding : ContactState::Locked;
  c[1].slideDirection = pattern & 2 ? 1 : 0;
  return c;
}

/// Feeds the sequence and returns the 1-based record at which a period is first reported (and
/// which), or {0, 0}.
std::pair<int, int> firstReport(const std::vector<int>& sequence) {
  solver::StateCycleDetector d;
  for (size_t k = 0; k < sequence.size(); ++k)
    if (const int p = d.record(statesOf(sequence[k])); p > 0) return {static_cast<int>(k) + 1, p};
  return {0, 0};
}

}  // namespace

TEST(StateCycle, TwoCycleIsReportedAfterThreeRepeats) {
  EXPECT_EQ(firstReport({0, 1, 0, 1, 0, 1, 0, 1, 0, 1}), std::make_pair(8, 2));
}

TEST(StateCycle, LongerPeriodsAfterAPrefix) {
  // Three non-repeating iterations, then a period of 3: reported at 3 + 4·3 = 15.
  EXPECT_EQ(firstReport({3, 3, 3, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1}), std::make_pair(15, 3));
  // Period 4 (0 0 1 1): at 4·4 = 16.
  EXPECT_EQ(firstReport({0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0}), std::make_pair(16, 4));
}

TEST(StateCycle, ConstantStatesAndSettlingAreNoCycle) {
  // Constant states: the friction forces may still be settling; not a cycle.
  EXPECT_EQ(firstReport(std::vector<int>(30, 2)), std::make_pair(0, 0));
  // A cycle that breaks before its third repeat is not reported.
  EXPECT_EQ(firstReport({0, 1, 0, 1, 0, 1, 0, 3, 3, 3, 3, 3, 3, 3}), std::make_pair(0, 0));
}

TEST(StateCycle, PeriodsBeyondTheLimitAreLeftToTheIterationLimit) {
  std::vector<int> seven;
  for (int k = 0; k < 40; ++k) seven.push_back(k % 7 == 0 ? 1 : 0);  // period 7 > kMaxPeriod
  EXPECT_EQ(firstReport(seven), std::make_pair(0, 0));
}
