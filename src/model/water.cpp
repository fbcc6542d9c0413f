#include "ddaslope/model/water.hpp"

#include <algorithm>
#include <cmath>

namespace ddaslope::model {

std::vector<Vec2> groundSurface(const std::vector<Block>& blocks) {
  std::vector<double> xs;
  for (const Block& b : blocks)
    for (const Vec2& v : b.vertices) xs.push_back(v.x());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::vector<Vec2> line;
  for (double x : xs) {
    double top = -INFINITY;
    for (const Block& b : blocks)
      for (size_t k = 0; k < b.vertices.size(); ++k) {
        const Vec2 &p = b.vertices[k], &q = b.vertices[(k + 1) % b.vertices.size()];
        if (x < std::min(p.x(), q.x()) || x > std::max(p.x(), q.x())) continue;
        // A vertical edge at x reaches its upper end; another edge crosses x once.
        const double y = p.x() == q.x() ? std::max(p.y(), q.y()) : p.y() + (q.y() - p.y()) * (x - p.x()) / (q.x() - p.x());
        top = std::max(top, y);
      }
    line.emplace_back(x, top);
  }
  return line;
}

WaterTable porePressureRatio(const std::vector<Block>& blocks, double ru, double groundUnitWeight) {
  WaterTable w;
  w.line = groundSurface(blocks);
  w.unitWeight = ru * groundUnitWeight;
  w.ru = ru;
  return w;
}

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
  if (grid) return grid->at(p);
  return std::max(0.0, unitWeight * (headAt(p.x()) - p.y()));
}

}  // namespace ddaslope::model
