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
  const bool categories = !plot.xCategories.empty();
  const double dx = categories ? 1 : tickStep(x1 - x0, 8), dy = tickStep(y1 - y0, 6);
  if (categories) {
    x0 = 0.5, x1 = plot.xCategories.size() + 0.5;
    // Bars reach across the plot: headroom above them for the legend, which names them.
    const double legend = std::min(0.6, (28.0 + 20.0 * plot.series.size()) / (height - top - bottom));
    y1 = y0 + (y1 - y0) / (1 - legend);
  }
  else x0 = std::floor(x0 / dx) * dx, x1 = std::ceil(x1 / dx) * dx;
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
  if (categories) {
    // Each category's name under its place, in a smaller font where it would not fit its share.
    const double share = (px(x1) - px(x0)) / plot.xCategories.size();
    for (size_t k = 0; k < plot.xCategories.size(); ++k) {
      const std::string& name = plot.xCategories[k];
      double size = 13;
      cairo_text_extents_t e;
      for (; size > 8; size -= 0.5) {
        cairo_set_font_size(cr, size);
        cairo_text_extents(cr, name.c_str(), &e);
        if (e.x_advance <= 0.95 * share) break;
      }
      cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
      text(cr, px(k + 1.0), py(y0) + 8, name, 0.5, 1);
    }
    cairo_set_font_size(cr, 13);
  } else {
    grid(true, x0, x1, dx);
  }
  grid(false, y0, y1, dy);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, px(x0), py(y1), px(x1) - px(x0), py(y0) - py(y1));
  cairo_stroke(cr);
  cairo_set_font_size(cr, 15);
  text(cr, (px(x0) + px(x1)) / 2, 30, plot.title, 0.5, 0);
  text(cr, (px(x0) + px(x1)) / 2, height - 22, plot.xLabel, 0.5, 0);
  text(cr, 28, (py(y0) + py(y1)) / 2, plot.yLabel, 0.5, 0, -M_PI / 2);
  // Series.
  // Eight colours a reader tells apart (the first four as before, then orange, black, sky blue, pink).
  const double colours[][3] = {{0.12, 0.35, 0.70}, {0.80, 0.25, 0.15}, {0.15, 0.60, 0.25}, {0.50, 0.30, 0.65},
                               {0.90, 0.60, 0.00}, {0.10, 0.10, 0.10}, {0.34, 0.71, 0.91}, {0.80, 0.47, 0.65}};
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
    const double* c = colours[k % 8];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 2);
    // Past eight series the colours come round again, dashed (then dotted): 24 series stay apart.
    const double dashes[][2] = {{8, 4}, {2, 3}};
    if (k >= 8) cairo_set_dash(cr, dashes[(k / 8 - 1) % 2], 2, 0);
    else cairo_set_dash(cr, nullptr, 0, 0);
    if (s.filled && !s.x.empty()) {
      cairo_new_path(cr);
      for (size_t i = 0; i < s.x.size(); ++i) cairo_line_to(cr, px(s.x[i]), py(s.y[i]));
      cairo_close_path(cr);
      cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.55);
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      cairo_stroke(cr);
    }
    bool pen = false;
    for (size_t i = 0; i < s.x.size() && s.lines && !s.filled; ++i) {
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
          cairo_new_path(cr);
          cairo_arc(cr, px(s.x[i]), py(s.y[i]), s.markerRadius, 0, 2 * M_PI);
          if (s.markerRadius > 3.5) {
            // A large marker stands out on a cloud of small ones: filled, with a white ring.
            cairo_fill_preserve(cr);
            cairo_set_source_rgb(cr, 1, 1, 1);
            cairo_set_line_width(cr, 1.5);
            cairo_stroke(cr);
            cairo_set_source_rgb(cr, c[0], c[1], c[2]);
          } else {
            cairo_fill(cr);
          }
        }
    // Legend, top right.
    const double ly = top + 18 + 20 * k;
    if (s.filled) {
      cairo_rectangle(cr, legendX + 6, ly - 6, 13, 12);
      cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.55);
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      cairo_stroke(cr);
    } else if (s.lines) {
      cairo_move_to(cr, legendX, ly);
      cairo_line_to(cr, legendX + 25, ly);
      cairo_stroke(cr);
    } else {
      cairo_new_path(cr);
      cairo_arc(cr, legendX + 12.5, ly, 3.5, 0, 2 * M_PI);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, legendX + 32, ly, s.label, 0, 0.35);
  }
  cairo_destroy(cr);
  const cairo_status_t st = cairo_surface_write_to_png(surface, (path + ".tmp").c_str());
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS || std::rename((path + ".tmp").c_str(), path.c_str()) != 0)
    throw InputError(path, "", "cannot write the picture");
}

void writePng(const HeatMap& m, const std::string& path) {
  const int width = 820, height = 600;
  const double left = 90, right = 140, top = 50, bottom = 70;
  const size_t nx = m.x.size(), ny = m.y.size();
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& row : m.values)
    for (double v : row)
      if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) lo = 1e-12, hi = 1;
  const double llo = std::log10(lo), lhi = std::log10(hi);
  const double x0 = m.x.front(), x1 = m.x.back(), y0 = m.y.front(), y1 = m.y.back();
  const double pw = width - left - right, ph = height - top - bottom;
  const auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  const auto py = [&](double y) { return height - bottom - (y - y0) / (y1 - y0) * ph; };
  // Viridis-like ramp: dark blue (low misfit) to yellow (high).
  const auto colour = [](double t, double* c) {
    const double k[5][3] = {{0.27, 0.00, 0.33}, {0.23, 0.32, 0.55}, {0.13, 0.57, 0.55}, {0.37, 0.79, 0.38}, {0.99, 0.91, 0.14}};
    t = std::clamp(t, 0.0, 1.0) * 4;
    const int i = std::min(3, static_cast<int>(t));
    const double f = t - i;
    for (int a = 0; a < 3; ++a) c[a] = k[i][a] * (1 - f) + k[i + 1][a] * f;
  };
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double cw = pw / (nx - 1), ch = ph / (ny - 1);
  double c[3];
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j) {
      const double v = m.values[i][j];
      colour(std::isfinite(v) && v > 0 ? (std::log10(v) - llo) / (lhi - llo) : 0, c);
      cairo_set_source_rgb(cr, c[0], c[1], c[2]);
      cairo_rectangle(cr, px(m.x[i]) - cw / 2, py(m.y[j]) - ch / 2, cw + 0.5, ch + 0.5);
      cairo_fill(cr);
    }
  cairo_reset_clip(cr);
  cairo_set_source_rgb(cr, 1, 1, 1);  // white margins over the half cells at the edges
  cairo_rectangle(cr, 0, 0, width, top), cairo_rectangle(cr, 0, height - bottom, width, bottom);
  cairo_rectangle(cr, 0, 0, left, height), cairo_rectangle(cr, width - right, 0, right, height);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, left, top, pw, ph);
  cairo_stroke(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  char buf[32];
  for (int k = 0; k <= 4; ++k) {
    const double x = x0 + (x1 - x0) * k / 4, y = y0 + (y1 - y0) * k / 4;
    std::snprintf(buf, sizeof buf, "%.4g", x);
    text(cr, px(x), height - bottom + 8, buf, 0.5, 1);
    std::snprintf(buf, sizeof buf, "%.4g", y);
    text(cr, left - 8, py(y), buf, 1, 0.5);
  }
  // Colour bar with decades.
  for (int k = 0; k < 100; ++k) {
    colour(k / 99.0, c);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_rectangle(cr, width - right + 20, height - bottom - ph * (k + 1) / 100.0, 20, ph / 100.0 + 0.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  for (int k = 0; k <= 4; ++k) {
    std::snprintf(buf, sizeof buf, "%.2g", std::pow(10, llo + (lhi - llo) * k / 4));
    text(cr, width - right + 46, height - bottom - ph * k / 4, buf, 0, 0.5);
  }
  // Marker at the estimate.
  cairo_set_source_rgb(cr, 1, 0.2, 0.2);
  cairo_set_line_width(cr, 2.5);
  cairo_new_path(cr);
  cairo_arc(cr, px(m.markX), py(m.markY), 7, 0, 2 * M_PI);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_font_size(cr, 15);
  text(cr, left + pw / 2, 30, m.title, 0.5, 0);
  text(cr, left + pw / 2, height - 22, m.xLabel, 0.5, 0);
  text(cr, 28, top + ph / 2, m.yLabel, 0.5, 0, -M_PI / 2);
  text(cr, width - 8, top + ph / 2, m.valueLabel, 0.5, 0, -M_PI / 2);
  cairo_destroy(cr);
  const cairo_status_t st = cairo_surface_write_to_png(surface, (path + ".tmp").c_str());
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS || std::rename((path + ".tmp").c_str(), path.c_str()) != 0)
    throw InputError(path, "", "cannot write the picture");
}

}  // namespace ddaslope::io
