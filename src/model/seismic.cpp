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

Vec2 GroundMotion::meanOver(double t0, double t1) const {
  if (times.empty() || !(t1 > t0) || t1 <= times.front() || t0 >= times.back()) return Vec2::Zero();
  // Trapezoids of the piecewise-linear record over the overlap of [t0, t1] with each interval.
  Vec2 integral = Vec2::Zero();
  const double a = std::max(t0, times.front()), b = std::min(t1, times.back());
  size_t k = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), a) - times.begin());
  double left = a;
  Vec2 atLeft = at(a);
  while (left < b) {
    const double right = k < times.size() ? std::min(b, times[k]) : b;
    const Vec2 atRight = at(right);
    integral += 0.5 * (right - left) * (atLeft + atRight);
    left = right;
    atLeft = atRight;
    ++k;
  }
  return integral / (t1 - t0);
}

Vec2 SeismicLoad::toModelFrame(const Vec2& horizontalUp, const Vec2& gravity) {
  const double g = gravity.norm();
  if (!(g > 0)) return horizontalUp;
  const Vec2 up = -gravity / g;
  const Vec2 horizontal(up.y(), -up.x());  // up turned clockwise: +x when gravity is along −y
  return horizontalUp.x() * horizontal + horizontalUp.y() * up;
}

Vec2 SeismicLoad::pseudoStatic(const Vec2& gravity) const {
  return toModelFrame(Vec2(kh, kv) * gravity.norm(), gravity);
}

}  // namespace ddaslope::model
