#include "ddaslope/io/line_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ddaslope/core/errors.hpp"

namespace ddaslope::io {
namespace {

/// A "nice" tick step (1, 2 or 5 × 10^k) giving about `count` ticks over `range`.
double tickStep(double range, int count) {
  const double raw = range / count, mag = std::pow(10, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) return m * mag;
  return 10 * mag;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double alignX, double alignY, double angle = 0) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  cairo_move_to(cr, -alignX * e.width - e.x_bearing, alignY * e.height);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

}  // namespace

void writePng(const LinePlot& plot, const std::string& path) {
  const int width = 800, height = 560;
  const double left = 90, right = 30, top = 50, bottom = 70;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& s : plot.series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    }
  if (!(x0 <= x1)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (x1 == x0) x0 -= 1, x1 += 1;
  if (y1 == y0) y0 -= 1, y1 += 1;
  const double dx = tickStep(x1 - x0, 8), dy = tickStep(y1 - y0, 6);
  x0 = std::floor(x0 / dx) * dx, x1 = std::ceil(x1 / dx) * dx;
  y0 = std::floor(y0 / dy) * dy, y1 = std::ceil(y1 / dy) * dy;
  const auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (width - left - right); };
  const auto py = [&](double y) { return height - bottom - (y - y0) / (y1 - y0) * (height - top - bottom); };

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  // Grid and tick labels.
  cairo_set_line_width(cr, 1);
  char buf[32];
  // One grid line and label per tick; `vertical` lines carry x ticks.
  const auto grid = [&](bool vertical, double lo, double hi, double step) {
    for (double v = lo; v <= hi + 1e-9 * step; v += step) {
      const double ax = vertical ? px(v) : px(x0), ay = vertical ? py(y0) : py(v);
      cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
      cairo_move_to(cr, ax, ay);
      cairo_line_to(cr, vertical ? ax : px(x1), vertical ? py(y1) : ay);
      cairo_stroke(cr);
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 * step ? 0.0 : v);
      if (vertical) text(cr, ax, ay + 8, buf, 0.5, 1);
      else text(cr, ax - 8, ay, buf, 1, 0.5);
    }
  };
  grid(true, x0, x1, dx);
  grid(false, y0, y1, dy);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, px(x0), py(y1), px(x1) - px(x0), py(y0) - py(y1));
  cairo_stroke(cr);
  cairo_set_font_size(cr, 15);
  text(cr, (px(x0) + px(x1)) / 2, 30, plot.title, 0.5, 0);
  text(cr, (px(x0) + px(x1)) / 2, height - 22, plot.xLabel, 0.5, 0);
  text(cr, 28, (py(y0) + py(y1)) / 2, plot.yLabel, 0.5, 0, -M_PI / 2);
  // Series.
  const double colours[][3] = {{0.12, 0.35, 0.70}, {0.80, 0.25, 0.15}, {0.15, 0.60, 0.25}, {0.50, 0.30, 0.65}};
  cairo_set_font_size(cr, 13);
  double labelWidth = 0;
  for (const auto& s : plot.series) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.label.c_str(), &e);
    labelWidth = std::max(labelWidth, e.x_advance);
  }
  const double legendX = width - right - 45 - labelWidth;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const double* c = colours[k % 4];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 2);
    bool pen = false;
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.y[i])) {
        pen = false;
        continue;
      }
      pen ? cairo_line_to(cr, px(s.x[i]), py(s.y[i])) : cairo_move_to(cr, px(s.x[i]), py(s.y[i]));
      pen = true;
    }
    cairo_stroke(cr);
    if (s.markers)
      for (size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.y[i])) {
          cairo_arc(cr, px(s.x[i]), py(s.y[i]), 3.5, 0, 2 * M_PI);
          cairo_fill(cr);
        }
    // Legend, top right.
    const double ly = top + 18 + 20 * k;
    cairo_move_to(cr, legendX, ly);
    cairo_line_to(cr, legendX + 25, ly);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, legendX + 32, ly, s.label, 0, 0.35);
  }
  cairo_destroy(cr);
  const cairo_status_t st = cairo_surface_write_to_png(surface, (path + ".tmp").c_str());
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS || std::rename((path + ".tmp").c_str(), path.c_str()) != 0)
    throw InputError(path, "", "cannot write the picture");
}

}  // namespace ddaslope::io
