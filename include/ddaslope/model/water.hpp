#pragma once
// Water: a phreatic line (polyline) above which there is no water; below it the pressure is
// hydrostatic, p = γw (h(x) − y), on every block edge: outer faces and joint faces alike, so a
// sliding surface feels uplift. A horizontal reservoir level is a one-segment line.
#include <vector>

#include "ddaslope/core/types.hpp"

namespace ddaslope::model {

struct WaterTable {
  std::vector<Vec2> line;      ///< phreatic line, x increasing; extended flat beyond its ends
  double unitWeight = 9810;    ///< γw (N/m³)
  /// Optional reservoir history: the water level (m) at times (s), linear in between and held
  /// beyond the ends. When set, the line is horizontal at levelAt(t).
  std::vector<double> seriesTimes, seriesLevels;
  bool active() const { return !line.empty(); }
  /// Height of the phreatic line at x (m).
  double headAt(double x) const;
  /// Pressure at point p (Pa), zero above the line.
  double pressureAt(const Vec2& p) const;
  /// The water at time t: itself, or a horizontal level from the series.
  WaterTable at(double t) const;
  double levelAt(double t) const;
};

}  // namespace ddaslope::model
