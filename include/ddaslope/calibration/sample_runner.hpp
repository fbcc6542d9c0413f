#pragma once
// The samples of a probability study (issue #18) as independent jobs behind one small interface:
// a scheduler takes the indices to run, an evaluator (index → result) and a sink called once per
// finished sample. runSamplesOnThreads is the local scheduler; an MPI one (a rank per worker,
// results sent to rank 0's sink) can stand in for it without touching the rest, because a
// sample's values depend on its index only and the summary is made from the samples sorted by
// index.
#include <functional>
#include <string>
#include <vector>

#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::calibration {

using SampleEvaluator = std::function<SampleResult(int index)>;
using SampleSink = std::function<void(const SampleResult&)>;
/// Runs evaluate(i) for each of `indices` (in any order, on any worker) and passes every result
/// to `sink`, one call at a time.
using SampleScheduler =
    std::function<void(const std::vector<int>& indices, const SampleEvaluator& evaluate, const SampleSink& sink)>;

/// `threads` workers take the next index of `indices` as each frees up (dynamic balance: a
/// sample's cost varies with its strengths). `sink` is called under a lock, in completion order.
/// If an evaluation or the sink throws, no further index is started, the samples running finish
/// and reach the sink, and the first exception is rethrown.
void runSamplesOnThreads(const std::vector<int>& indices, int threads, const SampleEvaluator& evaluate,
                         const SampleSink& sink);

/// How a sample's scene is judged.
struct SampleSettings {
  model::ProbabilityMeasure measure = model::ProbabilityMeasure::Verdict;
  std::vector<int> fosJoints;  ///< factor of safety: joints reduced (empty: all)
  double fosWidth = 0.005;
  VerdictSettings verdict;
};

/// One sample: the verdict of one forward run (not converged: NotConverged), or a
/// strength-reduction search on one thread (calibration::factorOfSafety). Its outcome is then
/// the verdict of the search's run at F = 1, so that "fails" and F < 1 agree; NotConverged when
/// the search found no bracket ("no_bracket") or its failing end is a run that did not converge.
/// `inputs` and `index` are copied into the result; runTime is its wall time.
SampleResult evaluateSample(const model::Scene& scene, const SampleSettings& settings, int index,
                            const std::vector<double>& inputs);

}  // namespace ddaslope::calibration
