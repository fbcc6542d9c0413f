#include "ddaslope/solver/state_cycle.hpp"

#include <cstddef>

namespace ddaslope::solver {

int StateCycleDetector::record(const std::vector<contact::Contact>& contacts) {
  std::vector<std::uint8_t> states(contacts.size());
  for (std::size_t q = 0; q < contacts.size(); ++q) {
    const contact::Contact& c = contacts[q];
    states[q] = static_cast<std::uint8_t>(static_cast<int>(c.state) * 6 + (c.slideDirection + 1) * 2 + c.bonded);
  }
  history_.push_back(std::move(states));
  const std::size_t window = static_cast<std::size_t>((kRepeats + 1) * kMaxPeriod);
  if (history_.size() > window) history_.pop_front();
  const std::size_t n = history_.size();
  for (std::size_t period = 2; period <= static_cast<std::size_t>(kMaxPeriod); ++period) {
    if (n < (kRepeats + 1) * period) break;
    bool repeats = true;
    for (std::size_t i = 0; repeats && i < kRepeats * period; ++i) repeats = history_[n - 1 - i] == history_[n - 1 - i - period];
    // Constant states are no cycle: the friction forces may still be settling.
    bool changes = false;
    for (std::size_t i = 1; !changes && i < period; ++i) changes = history_[n - 1] != history_[n - 1 - i];
    if (repeats && changes) return static_cast<int>(period);
  }
  return 0;
}

}  // namespace ddaslope::solver
