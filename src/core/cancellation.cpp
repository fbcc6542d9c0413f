#include "ddaslope/core/cancellation.hpp"

namespace ddaslope {
namespace {
thread_local const std::atomic<bool>* current = nullptr;
}  // namespace

CancellationScope::CancellationScope(const std::atomic<bool>& flag) : outer_(current) { current = &flag; }

CancellationScope::~CancellationScope() { current = outer_; }

void throwIfCancelled() {
  if (current && current->load(std::memory_order_relaxed)) throw Cancelled{};
}

}  // namespace ddaslope
