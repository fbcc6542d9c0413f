#include "ddaslope/calibration/position_search.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace ddaslope::calibration {
namespace {

/// The sample with the extreme value among those found; -1 if none.
int extremeSample(const std::vector<PositionSample>& s, double sign) {
  int best = -1;
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i].found && (best < 0 || sign * s[i].value < sign * s[best].value)) best = static_cast<int>(i);
  return best;
}

}  // namespace

PositionSearchResult searchLeastSafePosition(double lo, double hi, int points, bool maximise, double precision,
                                             const PositionEvaluator& evaluate) {
  const double sign = maximise ? -1 : 1;  // minimise sign × value
  points = std::max(points, 5);
  PositionSearchResult r;
  std::vector<double> coarse;
  for (int i = 0; i < points; ++i) coarse.push_back(lo + (hi - lo) * i / (points - 1));
  r.samples = evaluate(coarse);
  const int k = extremeSample(r.samples, sign);
  // The values' precision in their unit: as given, or that fraction of the extreme value (NaN
  // without one).
  const auto resolved = [precision](const PositionSample* extreme) {
    return precision >= 0 ? precision : extreme ? -precision * std::abs(extreme->value) : NAN;
  };
  // A position where the scene fails outright is less safe than any value: it is the answer, and
  // no finer grid can improve on it.
  const auto failing = std::find_if(r.samples.begin(), r.samples.end(), [](const PositionSample& s) { return s.fails; });
  if (failing != r.samples.end()) {
    r.found = r.fails = true;
    r.best = r.flatLo = r.flatHi = failing->x;
    for (const PositionSample& s : r.samples)
      if (s.fails) r.flatLo = std::min(r.flatLo, s.x), r.flatHi = std::max(r.flatHi, s.x);
    r.precision = resolved(nullptr);
    return r;
  }
  r.tied = k >= 0 && std::all_of(r.samples.begin(), r.samples.end(), [&](const PositionSample& s) {
             return s.found && s.value == r.samples[k].value;
           });
  if (k < 0 || r.tied) {
    r.best = r.flatLo = r.flatHi = NAN;
    r.precision = resolved(k < 0 ? nullptr : &r.samples[k]);
    return r;
  }
  r.found = true;
  // The finer grid between the best point's neighbours.
  const double step = (hi - lo) / (points - 1);
  const double a = std::max(lo, coarse[k] - step), b = std::min(hi, coarse[k] + step);
  std::vector<double> fine;
  for (int i = 1; i < points - 1; ++i) {
    const double x = a + (b - a) * i / (points - 1);
    if (std::abs(x - coarse[k]) > 1e-9 * (hi - lo)) fine.push_back(x);
  }
  for (const PositionSample& s : evaluate(fine)) r.samples.push_back(s);
  std::sort(r.samples.begin(), r.samples.end(), [](const auto& p, const auto& q) { return p.x < q.x; });

  // The parabola through the samples in [a, b], in a coordinate centred and scaled on them.
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  std::vector<const PositionSample*> near;
  for (const PositionSample& s : r.samples)
    if (s.found && s.x >= a - 1e-12 * (hi - lo) && s.x <= b + 1e-12 * (hi - lo)) near.push_back(&s);
  const int kBest = extremeSample(r.samples, sign);
  r.best = r.samples[kBest].x;
  double c1 = 0, c2 = 0;
  if (near.size() >= 4) {
    Eigen::MatrixXd A(near.size(), 3);
    Eigen::VectorXd y(near.size());
    for (size_t i = 0; i < near.size(); ++i) {
      const double t = (near[i]->x - mid) / half;
      A.row(i) << 1, t, t * t;
      y[i] = sign * near[i]->value;
    }
    const Eigen::Vector3d c = A.colPivHouseholderQr().solve(y);
    c1 = c[1], c2 = c[2];
    const double vertex = c2 > 0 ? -c1 / (2 * c2) : NAN;
    if (std::isfinite(vertex) && std::abs(vertex) <= 1) {
      r.best = mid + half * vertex;
      r.fitted = true;
    }
  }
  r.precision = resolved(&r.samples[kBest]);
  // Within the precision of the extreme: by the parabola where it was fitted, else by the samples.
  if (r.fitted) {
    const double reach = half * std::sqrt(std::max(r.precision, 0.0) / c2);
    r.flatLo = std::max(lo, r.best - reach), r.flatHi = std::min(hi, r.best + reach);
  } else {
    const double extreme = sign * r.samples[kBest].value;
    r.flatLo = r.flatHi = r.best;
    for (const PositionSample& s : r.samples)
      if (s.found && sign * s.value <= extreme + r.precision) r.flatLo = std::min(r.flatLo, s.x), r.flatHi = std::max(r.flatHi, s.x);
  }
  r.atEnd = !r.fitted && (r.best <= lo + 1e-9 * (hi - lo) || r.best >= hi - 1e-9 * (hi - lo));
  return r;
}

}  // namespace ddaslope::calibration
