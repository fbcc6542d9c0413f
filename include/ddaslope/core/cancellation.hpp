#pragma once
// Stopping work that another thread no longer needs: a search's trial run ahead of need whose
// branch the search did not take. The thread that does the work opens a scope on a flag; the
// work checks at its cancellation points (a simulation's steps) and unwinds with `Cancelled`
// once the flag is set. Work outside any scope is never cancelled.
#include <atomic>

namespace ddaslope {

/// Thrown at a cancellation point of a thread whose scope's flag is set. Not a std::exception:
/// it is no error, and handlers of errors must not take it for one.
struct Cancelled {};

/// While alive, the current thread's cancellation points watch `flag` (scopes nest: the inner
/// one rules until it closes).
class CancellationScope {
 public:
  explicit CancellationScope(const std::atomic<bool>& flag);
  ~CancellationScope();
  CancellationScope(const CancellationScope&) = delete;
  CancellationScope& operator=(const CancellationScope&) = delete;

 private:
  const std::atomic<bool>* outer_;
};

/// A cancellation point: throws Cancelled if the current thread's scope's flag is set.
void throwIfCancelled();

}  // namespace ddaslope
