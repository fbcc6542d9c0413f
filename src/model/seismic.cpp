#include "ddaslope/model/seismic.hpp"

#include <algorithm>

namespace ddaslope::model {

Vec2 GroundMotion::at(double t) const {
  if (times.empty() || t < times.front() || t > times.back()) return Vec2::Zero();
  const size_t hi = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  if (hi >= times.size()) return {horizontal.back(), vertical.empty() ? 0.0 : vertical.back()};
  const size_t lo = hi - 1;
  const double w = (t - times[lo]) / (times[hi] - times[lo]);
  const auto lerp = [&](const std::vector<double>& a) { return a.empty() ? 0.0 : (1 - w) * a[lo] + w * a[hi]; };
  return {lerp(horizontal), lerp(vertical)};
}

}  // namespace ddaslope::model
