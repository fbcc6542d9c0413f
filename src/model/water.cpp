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

double WaterTable::levelAt(double t) const {
  if (t <= seriesTimes.front()) return seriesLevels.front();
  if (t >= seriesTimes.back()) return seriesLevels.back();
  const size_t k = std::upper_bound(seriesTimes.begin(), seriesTimes.end(), t) - seriesTimes.begin();
  const double w = (t - seriesTimes[k - 1]) / (seriesTimes[k] - seriesTimes[k - 1]);
  return seriesLevels[k - 1] + w * (seriesLevels[k] - seriesLevels[k - 1]);
}

WaterTable WaterTable::at(double t) const {
  if (seriesTimes.empty()) return *this;
  WaterTable w = *this;
  const double y = levelAt(t);
  w.line = {{0, y}, {1, y}};
  return w;
}

double WaterTable::pressureAt(const Vec2& p) const {
  return std::max(0.0, unitWeight * (headAt(p.x()) - p.y()));
}

}  // namespace ddaslope::model
