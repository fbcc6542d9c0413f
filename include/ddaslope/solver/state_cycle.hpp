#pragma once
// Detects an open-close iteration caught in a cycle. The iteration is deterministic in the
// contact states: once the states of all contacts repeat with a period P (a contact that opens
// under the solution with it closed and closes under the one with it open, or load passed around
// a ring of contacts at the friction limit), the remaining iterations only retrace the cycle
// and the step will be cut at the iteration limit anyway. Cycles of short period set in within
// the first third of the iterations allowed: stopping them saves most of the work they would cost.
// Three full repeats are required: after two, a cycle can still, rarely, break out and converge
// (the state vector is not the whole iteration state: normal forces and lock positions ride
// along); docs/performance.md, "Measurements behind the solver's constants", has the counts.
#include <cstdint>
#include <deque>
#include <vector>

#include "ddaslope/contact/contact.hpp"

namespace ddaslope::solver {

class StateCycleDetector {
 public:
  /// Longest period looked for, and how many times the period must have been retraced in full.
  static constexpr int kMaxPeriod = 6;
  static constexpr int kRepeats = 3;

  /// Records the states after one iteration. Returns the period P ≥ 2 if the last kRepeats·P
  /// records each equal the record P iterations before them, else 0.
  int record(const std::vector<contact::Contact>& contacts);

 private:
  std::deque<std::vector<std::uint8_t>> history_;  ///< newest last
};

}  // namespace ddaslope::solver
