#pragma once
// Uncertain inputs of a case for a probability study (docs/probability.md): numbers of
// the case named by their JSON path, each with a distribution, the correlations between them, and
// how they are sampled and judged. Plain data: io/probability_reader.cpp reads it,
// calibration/probability.cpp samples it.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace ddaslope::model {

enum class DistributionKind { Normal, Lognormal, Uniform, TruncatedNormal };

/// One input's marginal distribution, in the units of its case value (degrees for angles).
struct Distribution {
  DistributionKind kind = DistributionKind::Normal;
  /// Normal and lognormal: the mean and standard deviation of the value itself (a lognormal's
  /// log has σ² = ln(1 + (sd/mean)²)). Truncated normal: those of the normal before truncation.
  double mean = 0, sd = 0;
  /// Uniform: the bounds (both required). Truncated normal: either or both; the other is ±∞.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

struct UncertainInput {
  std::string path;  ///< a number of the case, e.g. "joints.sliding_plane.cohesion"
  Distribution distribution;
};

/// The correlation coefficient of the standard normals underlying inputs a and b (Nataf): equal
/// to the correlation of the values when both are normal, a little smaller in size otherwise.
struct InputCorrelation {
  int a = 0, b = 0;  ///< indices into ProbabilitySpec::inputs, a ≠ b
  double rho = 0;    ///< in (−1, 1)
};

enum class Sampling { MonteCarlo, LatinHypercube };

/// What one sample yields: a stability verdict (one forward run), or a strength-reduction factor
/// of safety (a search of forward runs).
enum class ProbabilityMeasure { Verdict, FactorOfSafety };

/// Where the samples are drawn: from the inputs' distribution (plain sampling), or around the
/// design point that FORM finds first, each sample weighted (importance sampling: small Pf), or
/// classified by a surrogate of F learnt from searches at the samples it is least sure of
/// (active learning, AK-MCS: small Pf, any number of failure regions).
enum class ProbabilityMethod { Sampling, ImportanceSampling, ActiveLearning };

struct ProbabilitySpec {
  std::vector<UncertainInput> inputs;
  std::vector<InputCorrelation> correlations;
  int samples = 0;  ///< N, in [1, 1e7]
  Sampling sampling = Sampling::LatinHypercube;
  ProbabilityMethod method = ProbabilityMethod::Sampling;
  ProbabilityMeasure measure = ProbabilityMeasure::Verdict;
  std::uint64_t seed = 1;  ///< with the sample index, the only source of a sample's random numbers
  /// FactorOfSafety: the joints whose strengths are reduced (empty: all) and the final bracket
  /// width of F per sample (its error is at most half of it).
  std::vector<std::string> fosJoints;
  double fosWidth = 0.005;
};

}  // namespace ddaslope::model
