#pragma once
// Line plots as PNG through cairo (only line_plot.cpp includes cairo).
#include <string>
#include <vector>

namespace ddaslope::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool markers = true;
};

struct LinePlot {
  std::string title, xLabel, yLabel;
  std::vector<PlotSeries> series;
};

/// Writes the plot (800 × 560 px) to `path`. Throws InputError if the file cannot be written.
void writePng(const LinePlot& plot, const std::string& path);

}  // namespace ddaslope::io
