#include "ddaslope/calibration/sample_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "ddaslope/calibration/strength_search.hpp"

namespace ddaslope::calibration {

void runSamplesOnThreads(const std::vector<int>& indices, int threads, const SampleEvaluator& evaluate,
                         const SampleSink& sink) {
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::exception_ptr first;
  const auto work = [&] {
    for (size_t k = next++; k < indices.size() && !stop; k = next++) {
      try {
        const SampleResult r = evaluate(indices[k]);
        const std::lock_guard<std::mutex> lock(mutex);
        sink(r);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!first) first = std::current_exception();
        stop = true;
      }
    }
  };
  std::vector<std::thread> pool;
  const int n = std::clamp(threads, 1, std::max(1, static_cast<int>(indices.size())));
  for (int t = 1; t < n; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (first) std::rethrow_exception(first);
}

SampleResult evaluateSample(const model::Scene& scene, const SampleSettings& settings, int index,
                            const std::vector<double>& inputs) {
  const auto t0 = std::chrono::steady_clock::now();
  SampleResult out;
  out.index = index;
  out.inputs = inputs;
  if (settings.measure == model::ProbabilityMeasure::Verdict) {
    const TrialResult r = judgeStability(scene, settings.verdict);
    out.outcome = !r.converged ? SampleOutcome::NotConverged : r.stable ? SampleOutcome::Stable : SampleOutcome::Fails;
    out.rule = name(r.rule);
    out.maxDisplacement = r.maxDisplacement;
  } else {
    SearchSettings s;
    s.verdict = settings.verdict;
    s.threads = 1;  // the samples run in parallel instead
    const FactorOfSafetyResult r = factorOfSafety(scene, settings.fosJoints, settings.fosWidth, s);
    // The search always starts at F = 1: that run is the unreduced slope's verdict.
    const auto atOne = std::find_if(r.trials.begin(), r.trials.end(), [](const TrialRecord& t) { return t.value == 1; });
    const auto failingEnd = std::find_if(r.trials.begin(), r.trials.end(),
                                         [&](const TrialRecord& t) { return t.value == r.failingEnd; });
    if (atOne != r.trials.end()) {
      out.rule = name(atOne->result.rule);
      out.maxDisplacement = atOne->result.maxDisplacement;
    }
    if (!r.found) {
      out.outcome = SampleOutcome::NotConverged;
      out.rule = "no_bracket";
    } else if (atOne == r.trials.end() || (failingEnd != r.trials.end() && !failingEnd->result.converged)) {
      out.outcome = SampleOutcome::NotConverged;  // F rests on a run that did not converge
      out.rule = name(VerdictRule::NotConverged);
    } else {
      out.outcome = atOne->result.stable ? SampleOutcome::Stable : SampleOutcome::Fails;
      out.factor = r.factor;
    }
  }
  out.runTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace ddaslope::calibration
