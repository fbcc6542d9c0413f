#include "ddaslope/calibration/sample_runner.hpp"

#include <algorithm>
#include <iterator>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "ddaslope/calibration/strength_search.hpp"
#include "ddaslope/core/byte_record.hpp"

namespace ddaslope::calibration {

std::string packSample(const SampleResult& r) {
  BytePacker b;
  b.put(r.index).put(r.inputs.size());
  for (double v : r.inputs) b.put(v);
  b.put(r.outcome).put(r.rule).put(r.factor).put(r.maxDisplacement).put(r.runTime).put(r.runs);
  return b.bytes();
}

SampleResult unpackSample(const std::string& bytes) {
  ByteUnpacker b(bytes);
  SampleResult r;
  r.index = b.get<int>();
  r.inputs.resize(b.get<size_t>());
  for (double& v : r.inputs) v = b.get<double>();
  r.outcome = b.get<SampleOutcome>();
  r.rule = b.getString();
  r.factor = b.get<double>();
  r.maxDisplacement = b.get<double>();
  r.runTime = b.get<double>();
  r.runs = b.get<int>();
  return r;
}

SampleResult evaluateSample(const model::Scene& scene, const SampleSettings& settings, int index,
                            const std::vector<double>& inputs) {
  const auto t0 = std::chrono::steady_clock::now();
  SampleResult out;
  out.index = index;
  out.inputs = inputs;
  if (settings.measure == model::ProbabilityMeasure::Verdict) {
    const TrialResult r = judgeStability(scene, settings.verdict);
    // An undecided verdict is not a failure: counted with the runs that did not converge, which
    // the study reports apart and bounds Pf with.
    out.outcome = !r.converged || r.undecided ? SampleOutcome::NotConverged
                  : r.stable                  ? SampleOutcome::Stable
                                              : SampleOutcome::Fails;
    out.rule = name(r.rule);
    out.maxDisplacement = r.maxDisplacement;
  } else {
    SearchSettings s;
    s.verdict = settings.verdict;
    s.threads = 1;  // the samples run in parallel instead
    const FactorOfSafetyResult r = factorOfSafety(scene, settings.fosJoints, settings.fosWidth, s);
    out.runs = static_cast<int>(r.trials.size());
    // The search always starts at F = 1: that run is the unreduced slope's verdict (its review's
    // re-run, if any, which the trials list after it).
    const auto one = std::find_if(r.trials.rbegin(), r.trials.rend(), [](const TrialRecord& t) { return t.value == 1; });
    const auto atOne = one == r.trials.rend() ? r.trials.end() : std::prev(one.base());
    const auto last = std::find_if(r.trials.rbegin(), r.trials.rend(),
                                   [&](const TrialRecord& t) { return t.value == r.failingEnd; });
    const auto failingEnd = last == r.trials.rend() ? r.trials.end() : std::prev(last.base());
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
    } else if (atOne->result.undecided) {
      out.outcome = SampleOutcome::NotConverged;
      out.rule = name(VerdictRule::Undecided);
    } else {
      out.outcome = atOne->result.stable ? SampleOutcome::Stable : SampleOutcome::Fails;
      out.factor = r.factor;
    }
  }
  out.runTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace ddaslope::calibration
