#pragma once
// One sample of a probability study: its forward run or search, and its result as
// bytes. The samples run on a task farm (core/task_farm.hpp: threads, or MPI ranks); a sample's
// values depend on its index only and the summary is made from the samples sorted by index, so
// the answer does not depend on the farm.
#include <functional>
#include <string>
#include <vector>

#include "ddaslope/calibration/probability.hpp"
#include "ddaslope/calibration/verdict.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::calibration {

/// A sample's result as bytes and back: what crosses between MPI ranks (core/task_farm.hpp).
std::string packSample(const SampleResult& r);
SampleResult unpackSample(const std::string& bytes);

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
