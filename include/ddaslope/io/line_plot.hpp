#pragma once
// Line plots as PNG through cairo (only line_plot.cpp includes cairo).
#include <string>
#include <vector>

namespace ddaslope::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool markers = true;
  bool lines = true;  ///< false: markers only (a scatter)
  double markerRadius = 3.5;  ///< px; larger markers are drawn with a white ring (a point to find)
  bool filled = false;  ///< the points close a shape drawn filled (a bar), its legend a square
};

struct LinePlot {
  std::string title, xLabel, yLabel;
  std::vector<PlotSeries> series;
  /// Non-empty: the x axis names categories, the k-th (from 0) at x = k + 1, instead of numbers.
  std::vector<std::string> xCategories = {};
};

/// Writes the plot (800 × 560 px) to `path`. Throws InputError if the file cannot be written.
void writePng(const LinePlot& plot, const std::string& path);

/// A scalar field on a regular grid: values[i][j] at (x[i], y[j]), drawn as coloured cells on
/// a log scale (misfits span decades), with a marker at (markX, markY).
struct HeatMap {
  std::string title, xLabel, yLabel, valueLabel;
  std::vector<double> x, y;
  std::vector<std::vector<double>> values;
  double markX = 0, markY = 0;
};
void writePng(const HeatMap& map, const std::string& path);

}  // namespace ddaslope::io
