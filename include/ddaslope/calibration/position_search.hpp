#pragma once
// The least safe position of a feature along a range (a tension crack behind the crest): the
// position where the factor of safety is least, or the critical strength greatest. Each value is
// a search of its own with a finite precision, and near the extreme the curve is flat (on Hoek &
// Bray's dry planar failure, far flatter than the searches' rounding), so a golden-section search
// would follow that rounding. Instead: a grid over the range, a finer grid around its best point, and a
// least-squares parabola through the fine points, whose vertex is the answer.
#include <functional>
#include <string>
#include <vector>

namespace ddaslope::calibration {

struct PositionSample {
  double x = 0;
  double value = 0;
  bool found = false;  ///< the search at x gave a value
  std::string message;  ///< why not, when it did not
  /// No value because the scene fails at every value the search tried (no F, no strength or
  /// support that holds): less safe than any value, where "held at every value" is safer.
  bool fails = false;
};

struct PositionSearchResult {
  /// Some position is least safe. When none gave a value, or every position of the range gave
  /// the same one (`tied`: a slope that stands without cohesion wherever its crack is), none is:
  /// `best` and the flat range are NaN, and the caller keeps the feature where the case puts it.
  bool found = false;
  bool tied = false;
  /// The least safe position is one where the scene fails at every value tried (`best`: the first
  /// such, `flatLo`–`flatHi` their span): the answer there is none, which the caller reports.
  bool fails = false;
  double best = 0;          ///< the least safe position
  bool atEnd = false;       ///< it lies at an end of the range (widen the range to look beyond)
  bool fitted = false;      ///< from the parabola's vertex (else the best sample)
  /// Positions whose value is within `precision` of the extreme: how sharply the range decides it.
  double flatLo = 0, flatHi = 0;
  /// The values' precision in their own unit (`precision` as given, or resolved from its fraction).
  double precision = 0;
  std::vector<PositionSample> samples;  ///< every position searched, by x
};

/// Values at a batch of positions (run at once by the caller).
using PositionEvaluator = std::function<std::vector<PositionSample>(const std::vector<double>& xs)>;

/// The extreme of the values over [lo, hi]: the least (`maximise` false: a factor of safety) or the
/// greatest (a critical strength). `points` positions per grid (≥ 5); `precision` is the values'
/// own (a search's bracket width); negative, it is that fraction of the extreme value's magnitude
/// (searches that narrow to a fraction of their answer).
PositionSearchResult searchLeastSafePosition(double lo, double hi, int points, bool maximise, double precision,
                                             const PositionEvaluator& evaluate);

}  // namespace ddaslope::calibration
