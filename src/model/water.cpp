#include "ddaslope/model/water.hpp"

#include <algorithm>

namespace ddaslope::model {

double WaterTable::headAt(double x) const {
  if (x <= line.front().x()) return line.front().y();
  if (x >= line.back().x()) return line.back().y();
  const auto it = std::upper_bound(line.begin(), line.end(), x, [](double v, const Vec2& p) { return v < p.x(); });
  const Vec2 &b = *it, &a = *(it - 1);
  return a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
}

double WaterTable::pressureAt(const Vec2& p) const {
  return std::max(0.0, unitWeight * (headAt(p.x()) - p.y()));
}

}  // namespace ddaslope::model
