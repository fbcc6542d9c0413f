#pragma once
// Water: a phreatic line (polyline) above which there is no water; below it the pressure is
// hydrostatic, p = γw (h(x) − y), on every block edge: outer faces and joint faces alike, so a
// sliding surface feels uplift. A horizontal reservoir level is a one-segment line.
#include <memory>
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/model/block.hpp"
#include "ddaslope/model/pressure_grid.hpp"

namespace ddaslope::model {

/// The ground surface of a scene: the upper envelope of its blocks, a point at every vertex's x
/// (between them the topmost edge is one straight edge, blocks not overlapping). A crack narrower
/// than the blocks' spacing of vertices is bridged.
std::vector<Vec2> groundSurface(const std::vector<Block>& blocks);

/// A pore-pressure ratio r_u = u/(γ h) (Bishop & Morgenstern 1960), h the depth below the ground
/// surface: u = r_u γ (ground(x) − y), a hydrostatic law with the ground for its line and r_u γ
/// for its unit weight (the WaterTable it returns), integrated as a water table is.
struct WaterTable;
WaterTable porePressureRatio(const std::vector<Block>& blocks, double ru, double groundUnitWeight);

struct WaterTable {
  std::vector<Vec2> line;      ///< phreatic line, x increasing; extended flat beyond its ends
  double unitWeight = 9810;    ///< γw (N/m³)
  /// Optional reservoir history: the water level (m) at times (s), linear in between and held
  /// beyond the ends. When set, the line is horizontal at levelAt(t).
  std::vector<double> seriesTimes, seriesLevels;
  /// Set when the pressure is r_u's (porePressureRatio): the ratio, for the record.
  double ru = 0;
  /// A pressure grid (water.pressure_grid) in place of the line: the pressure is the grid's.
  std::shared_ptr<const PressureGrid> grid;
  bool active() const { return !line.empty() || grid; }
  /// Height of the phreatic line at x (m); a line is needed (not with a grid).
  double headAt(double x) const;
  /// Pressure at point p (Pa), zero above the line.
  double pressureAt(const Vec2& p) const;
  /// The water at time t: itself, or a horizontal level from the series.
  WaterTable at(double t) const;
  double levelAt(double t) const;
};

}  // namespace ddaslope::model
