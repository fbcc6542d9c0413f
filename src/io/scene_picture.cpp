#include "ddaslope/io/scene_picture.hpp"

#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ddaslope/core/errors.hpp"
#include "ddaslope/geometry/polygon.hpp"

namespace ddaslope::io {

PictureFrame frameScene(const model::Scene& scene) {
  PictureFrame f;
  f.whole = geometry::boundingBox(scene.blocks.front().vertices);
  bool anyFree = false;
  geometry::Aabb free;
  for (const model::Block& b : scene.blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    f.whole.lo = f.whole.lo.cwiseMin(bb.lo);
    f.whole.hi = f.whole.hi.cwiseMax(bb.hi);
    f.initialCentroids.push_back(b.moments.centroid);
    if (b.fixed) continue;
    free = anyFree ? geometry::Aabb{free.lo.cwiseMin(bb.lo), free.hi.cwiseMax(bb.hi)} : bb;
    anyFree = true;
  }
  const Vec2 size = f.whole.hi - f.whole.lo;
  f.view = {f.whole.lo - 0.05 * size, f.whole.hi + 0.05 * size};
  if (anyFree) {
    // The free blocks with a quarter of their extent around them (room for their motion and
    // their neighbours), within the whole scene.
    const double margin = 0.25 * (free.hi - free.lo).maxCoeff();
    const geometry::Aabb zoom{(free.lo - Vec2(margin, margin)).cwiseMax(f.view.lo),
                              (free.hi + Vec2(margin, margin)).cwiseMin(f.view.hi)};
    const Vec2 z = zoom.hi - zoom.lo, v = f.view.hi - f.view.lo;
    if (z.x() * z.y() < 0.25 * v.x() * v.y()) {
      f.view = zoom;
      f.zoomed = true;
    }
  }
  return f;
}

namespace {

/// A tick spacing of 1, 2 or 5 × 10^k giving about `count` ticks over `range`.
double niceStep(double range, int count) {
  const double raw = range / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * power >= raw) return m * power;
  return 10 * power;
}

/// Blue (still) through yellow to red (moved most), for t in [0, 1].
void ramp(double t, double* c) {
  const double k[3][3] = {{0.35, 0.55, 0.85}, {0.98, 0.85, 0.30}, {0.85, 0.20, 0.15}};
  t = std::clamp(t, 0.0, 1.0) * 2;
  const int i = std::min(1, static_cast<int>(t));
  for (int a = 0; a < 3; ++a) c[a] = k[i][a] + (k[i + 1][a] - k[i][a]) * (t - i);
}

void label(cairo_t* cr, double x, double y, const std::string& text, double alignX, double alignY) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  cairo_move_to(cr, x - alignX * e.x_advance, y + alignY * e.height);
  cairo_show_text(cr, text.c_str());
}

std::string metres(double v) {
  char t[32];
  std::snprintf(t, sizeof t, "%g", std::abs(v) < 1e-9 ? 0.0 : v);
  return t;
}

}  // namespace

SceneState captureState(const solver::Simulation& sim) {
  SceneState s;
  s.scene = sim.scene();
  s.time = sim.time();
  for (const contact::Contact& c : sim.contacts().contacts())
    if (c.closed())
      s.contacts.push_back({c.key().vertexBlock, c.key().vertex, c.state == contact::ContactState::Locked});
  return s;
}

void writeScenePicture(const solver::Simulation& sim, const PictureFrame& frame, const std::string& path,
                       const std::string& title) {
  writeScenePicture(captureState(sim), frame, path, title);
}

void writeScenePicture(const SceneState& state, const PictureFrame& frame, const std::string& path,
                       const std::string& title, double displacementScale) {
  const model::Scene& scene = state.scene;
  // Equal scales in x and y, the plot at most 860 × 760 px; a flat view (a slab) is widened in
  // height around its middle so that the plot keeps 260 px.
  geometry::Aabb view = frame.view;
  if (frame.zoomed) {
    // Blocks that moved out of the zoomed view (a run-out) widen it: nothing free leaves the picture.
    for (const model::Block& b : scene.blocks) {
      if (b.fixed) continue;
      const geometry::Aabb bb = geometry::boundingBox(b.vertices);
      const Vec2 pad = 0.1 * (bb.hi - bb.lo);
      view.lo = view.lo.cwiseMin(bb.lo - pad);
      view.hi = view.hi.cwiseMax(bb.hi + pad);
    }
  }
  const double worldW = view.hi.x() - view.lo.x();
  double worldH = view.hi.y() - view.lo.y();
  const double scale = std::min(860 / worldW, 760 / worldH);
  if (worldH * scale < 260) {
    const double mid = 0.5 * (view.lo.y() + view.hi.y());
    worldH = 260 / scale;
    view.lo.y() = mid - worldH / 2;
    view.hi.y() = mid + worldH / 2;
  }
  const int left = 70, top = 40, plotW = static_cast<int>(std::ceil(worldW * scale)),
            plotH = static_cast<int>(std::ceil(worldH * scale));
  // Right of the plot: the colour bar, and the whole scene's inset below it when zoomed.
  const int width = left + std::max(plotW, 400) + (frame.zoomed ? 240 : 110);
  const int height = top + std::max(plotH, frame.zoomed ? 420 : 0) + 95;
  const auto px = [&](const Vec2& p) {
    return std::pair{left + (p.x() - view.lo.x()) * scale, top + (view.hi.y() - p.y()) * scale};
  };
  std::vector<double> moved(scene.blocks.size(), 0);
  double maxMoved = 0;
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    moved[b] = (scene.blocks[b].moments.centroid - frame.initialCentroids[b]).norm();
    if (!scene.blocks[b].fixed) maxMoved = std::max(maxMoved, moved[b]);
  }
  // The colours' and arrows' full scale: at least `displacementScale`, so that a slope at rest
  // (micrometres) is drawn blue, not red as if it were the most moved.
  const double fullScale = std::max(maxMoved, displacementScale);
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  // Everything of the scene stays inside the plot.
  cairo_save(cr);
  cairo_rectangle(cr, left, top, plotW, plotH);
  cairo_clip(cr);
  // Water below the phreatic line (a pore-pressure ratio or a pressure grid has no free water to
  // draw: the legend names it).
  if (scene.water.active() && scene.water.ru <= 0 && !scene.water.grid) {
    cairo_set_source_rgba(cr, 0.55, 0.75, 0.95, 0.5);
    const int steps = 200;
    for (int i = 0; i <= steps; ++i) {
      const double x = view.lo.x() + worldW * i / steps;
      const auto [sx, sy] = px({x, std::min(scene.water.headAt(x), view.hi.y())});
      i == 0 ? cairo_move_to(cr, sx, sy) : cairo_line_to(cr, sx, sy);
    }
    const auto [rx, ry] = px({view.hi.x(), view.lo.y()});
    const auto [lx, ly] = px(view.lo);
    cairo_line_to(cr, rx, ry);
    cairo_line_to(cr, lx, ly);
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  // A block's outline as a path, in its colour (grey fixed, else by displacement): the picture's
  // and the inset's.
  const auto blockPath = [&](size_t b, const auto& to) {
    const model::Block& blk = scene.blocks[b];
    for (size_t k = 0; k < blk.vertices.size(); ++k) {
      const auto [x, y] = to(blk.vertices[k]);
      k == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
    }
    cairo_close_path(cr);
    double c[3] = {0.78, 0.78, 0.78};
    if (!blk.fixed) ramp(fullScale > 0 ? moved[b] / fullScale : 0, c);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
  };
  // Blocks.
  cairo_set_line_width(cr, 1.2);
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    blockPath(b, px);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_stroke(cr);
  }
  // Water pressure on the free blocks' faces: a diagram outside each face, its depth the pressure
  // (the greatest 40 px), as the pressure on a sliding surface or crack is drawn by hand.
  double maxPressure = 0;
  if (scene.water.active()) {
    const model::WaterTable water = scene.water.at(state.time);
    // Faces between two free blocks are left out: their pressures cancel, and the diagrams of
    // both sides would hide each other.
    const double near = 1e-3 * std::max(worldW, worldH);
    const auto sharedWithAFreeBlock = [&](const model::Block& own, const Vec2& mid) {
      for (const model::Block& other : scene.blocks) {
        if (&other == &own || other.fixed) continue;
        for (size_t m = 0; m < other.vertices.size(); ++m)
          if (geometry::distanceToSegment(mid, other.vertices[m], other.vertices[(m + 1) % other.vertices.size()], nullptr) <= near)
            return true;
      }
      return false;
    };
    const auto forEachFace = [&](auto&& f) {
      for (const model::Block& blk : scene.blocks) {
        if (blk.fixed) continue;
        for (size_t k = 0; k < blk.vertices.size(); ++k) {
          const Vec2 &a = blk.vertices[k], &b = blk.vertices[(k + 1) % blk.vertices.size()];
          if (!sharedWithAFreeBlock(blk, 0.5 * (a + b))) f(a, b);
        }
      }
    };
    const auto samples = [&](const Vec2& a, const Vec2& b) {
      return std::clamp(static_cast<int>((b - a).norm() * scale / 6), 2, 400);
    };
    forEachFace([&](const Vec2& a, const Vec2& b) {
      const int n = samples(a, b);
      for (int i = 0; i <= n; ++i) maxPressure = std::max(maxPressure, water.pressureAt(a + (b - a) * (double(i) / n)));
    });
    if (maxPressure > 0) {
      cairo_set_line_width(cr, 0.8);
      forEachFace([&](const Vec2& a, const Vec2& b) {
        const int n = samples(a, b);
        const Vec2 d = (b - a).normalized(), outward(d.y(), -d.x());  // counter-clockwise blocks
        bool any = false;
        const auto [ax, ay] = px(a);
        cairo_new_path(cr);
        cairo_move_to(cr, ax, ay);
        for (int i = 0; i <= n; ++i) {
          const Vec2 q = a + (b - a) * (double(i) / n);
          const double depth = 40 * water.pressureAt(q) / maxPressure;
          any |= depth > 0;
          const auto [x, y] = px(q);
          cairo_line_to(cr, x + depth * outward.x(), y - depth * outward.y());
        }
        const auto [bx, by] = px(b);
        cairo_line_to(cr, bx, by);
        cairo_close_path(cr);
        if (!any) return;
        cairo_set_source_rgba(cr, 0.15, 0.4, 0.9, 0.35);
        cairo_fill_preserve(cr);
        cairo_set_source_rgba(cr, 0.1, 0.3, 0.8, 0.9);
        cairo_stroke(cr);
      });
    }
  }
  // Displacement vectors: from each free block's first centroid towards where it went, the
  // longest 40 px (a mechanism of centimetres on a slope of tens of metres is seen in them).
  if (fullScale > 0) {
    cairo_set_source_rgb(cr, 0.35, 0.0, 0.25);
    cairo_set_line_width(cr, 1.5);
    for (size_t b = 0; b < scene.blocks.size(); ++b) {
      if (scene.blocks[b].fixed || moved[b] < 0.05 * fullScale) continue;
      const Vec2 d = (scene.blocks[b].moments.centroid - frame.initialCentroids[b]) / fullScale;
      const auto [x, y] = px(scene.blocks[b].moments.centroid);
      const double ex = x + 40 * d.x(), ey = y - 40 * d.y(), len = 40 * d.norm();
      const double ux = (ex - x) / len, uy = (ey - y) / len;
      cairo_move_to(cr, x, y);
      cairo_line_to(cr, ex, ey);
      cairo_stroke(cr);
      cairo_move_to(cr, ex, ey);
      cairo_line_to(cr, ex - 7 * ux + 3.5 * uy, ey - 7 * uy - 3.5 * ux);
      cairo_line_to(cr, ex - 7 * ux - 3.5 * uy, ey - 7 * uy + 3.5 * ux);
      cairo_close_path(cr);
      cairo_fill(cr);
    }
  }
  // Contacts: green locked, orange sliding (open contacts are not drawn).
  for (const SceneState::ContactMark& c : state.contacts) {
    const auto [x, y] = px(scene.blocks[static_cast<size_t>(c.block)].vertices[static_cast<size_t>(c.vertex)]);
    if (c.locked) cairo_set_source_rgb(cr, 0.1, 0.6, 0.2);
    else cairo_set_source_rgb(cr, 0.95, 0.5, 0.0);
    cairo_new_path(cr);
    cairo_arc(cr, x, y, 3.5, 0, 2 * M_PI);
    cairo_fill(cr);
  }
  // Supports: a line from head to end with a plate at the head; dark blue while they hold,
  // magenta once yielded, grey dashed when slack or broken.
  for (const model::Support& b : scene.supports) {
    const auto [hx, hy] = px(b.head.current);
    const auto [ex, ey] = px(b.end.current);
    const bool carries = b.state == model::SupportState::Elastic || b.state == model::SupportState::Yielded;
    if (b.state == model::SupportState::Yielded) cairo_set_source_rgb(cr, 0.8, 0.0, 0.8);
    else if (carries) cairo_set_source_rgb(cr, 0.05, 0.1, 0.5);
    else cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
    const double dash[] = {6.0, 4.0};
    cairo_set_dash(cr, dash, carries ? 0 : 2, 0);
    cairo_set_line_width(cr, 2.5);
    cairo_move_to(cr, hx, hy);
    cairo_line_to(cr, ex, ey);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_rectangle(cr, hx - 4, hy - 4, 8, 8);
    cairo_fill(cr);
  }
  // Loads: an arrow towards each point load's point (edge loads: at their Gauss points).
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1.5);
  for (const model::PointLoad& l : scene.pointLoads) {
    const Vec2 f = l.at(state.time);
    if (!(f.norm() > 0)) continue;
    const auto [x, y] = px(l.point.current);
    const double ux = f.x() / f.norm(), uy = -f.y() / f.norm();  // picture y runs down
    const double len = 30;
    cairo_move_to(cr, x - len * ux, y - len * uy);
    cairo_line_to(cr, x, y);
    cairo_stroke(cr);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x - 8 * ux + 4 * uy, y - 8 * uy - 4 * ux);
    cairo_line_to(cr, x - 8 * ux - 4 * uy, y - 8 * uy + 4 * ux);
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  // Monitors: red crosses.
  cairo_set_source_rgb(cr, 0.85, 0.0, 0.0);
  cairo_set_line_width(cr, 2);
  cairo_set_font_size(cr, 11);
  for (const model::Monitor& m : scene.monitors) {
    const auto [x, y] = px(m.point.current);
    cairo_move_to(cr, x - 5, y - 5);
    cairo_line_to(cr, x + 5, y + 5);
    cairo_move_to(cr, x - 5, y + 5);
    cairo_line_to(cr, x + 5, y - 5);
    cairo_stroke(cr);
    // Named, as history.csv's columns and history.png's legend name it.
    cairo_move_to(cr, x + 7, y - 7);
    cairo_show_text(cr, m.id.c_str());
  }
  cairo_restore(cr);  // the plot's clip
  // The whole scene as an inset when the view is zoomed on the free blocks, the view marked.
  if (frame.zoomed) {
    const Vec2 size = frame.whole.hi - frame.whole.lo;
    const double k = std::min(200 / size.x(), 150 / size.y());
    const double ix = left + plotW + 22, iy = top + 260;
    const auto ipx = [&](const Vec2& p) {
      return std::pair{ix + (p.x() - frame.whole.lo.x()) * k, iy + (frame.whole.hi.y() - p.y()) * k};
    };
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_rectangle(cr, ix - 4, iy - 4, k * size.x() + 8, k * size.y() + 8);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    for (size_t b = 0; b < scene.blocks.size(); ++b) {
      blockPath(b, ipx);
      cairo_fill(cr);
    }
    const auto [vx0, vy0] = ipx({view.lo.x(), view.hi.y()});
    const auto [vx1, vy1] = ipx({view.hi.x(), view.lo.y()});
    cairo_set_source_rgb(cr, 0.85, 0.0, 0.0);
    cairo_set_line_width(cr, 1.5);
    cairo_rectangle(cr, vx0, vy0, vx1 - vx0, vy1 - vy0);
    cairo_stroke(cr);
  }
  // Axes in metres on the plot's frame.
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, left, top, plotW, plotH);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 11);
  const double step = niceStep(std::max(worldW, worldH), 8);
  for (double x = std::ceil(view.lo.x() / step) * step; x <= view.hi.x(); x += step) {
    const double sx = px({x, 0}).first;
    cairo_move_to(cr, sx, top + plotH);
    cairo_line_to(cr, sx, top + plotH + 5);
    cairo_stroke(cr);
    label(cr, sx, top + plotH + 10, metres(x), 0.5, 1);
  }
  for (double y = std::ceil(view.lo.y() / step) * step; y <= view.hi.y(); y += step) {
    const double sy = px({0, y}).second;
    cairo_move_to(cr, left - 5, sy);
    cairo_line_to(cr, left, sy);
    cairo_stroke(cr);
    label(cr, left - 8, sy, metres(y), 1, 0.5);
  }
  cairo_set_font_size(cr, 12);
  label(cr, left + plotW / 2.0, top + plotH + 32, "x (m)", 0.5, 0);
  cairo_save(cr);
  cairo_translate(cr, 30, top + plotH / 2.0);
  cairo_rotate(cr, -M_PI / 2);
  label(cr, 0, 0, "y (m)", 0.5, 0);
  cairo_restore(cr);
  // Colour bar of the displacement, right of the plot.
  const double barX = left + plotW + 22, barH = std::min(200.0, 0.8 * plotH);
  for (int i = 0; i < 100; ++i) {
    double c[3];
    ramp(i / 99.0, c);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_rectangle(cr, barX, top + barH * (1 - (i + 1) / 100.0), 14, barH / 100 + 0.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, barX, top, 14, barH);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 11);
  char top_[32];
  std::snprintf(top_, sizeof top_, "%.3g m", fullScale);
  label(cr, barX + 18, top, top_, 0, 0.5);
  label(cr, barX + 18, top + barH, "0", 0, 0.5);
  label(cr, barX, top + barH + 16, "block", 0, 0.5);
  label(cr, barX, top + barH + 30, "displacement", 0, 0.5);
  cairo_set_font_size(cr, 15);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_move_to(cr, 20, 26);
  cairo_show_text(cr, title.c_str());
  char legend[300];
  std::snprintf(legend, sizeof legend,
                "t = %.4g s   colour, arrows: block centre's displacement since drawn (full scale %.3g m; largest "
                "%.3g m)   contacts: green locked, orange sliding   x: monitors%s",
                state.time, fullScale, maxMoved, frame.zoomed ? "   inset: the whole scene, the view in red" : "");
  cairo_set_font_size(cr, 12);
  cairo_move_to(cr, 20, height - 26);
  cairo_show_text(cr, legend);
  if (!scene.supports.empty() || !scene.pointLoads.empty() || maxPressure > 0) {
    char water[120] = "";
    if (maxPressure > 0)
      std::snprintf(water, sizeof water, "blue: water pressure on the faces, up to %.3g kPa%s", maxPressure / 1e3,
                    scene.water.ru > 0   ? (" (r_u = " + std::to_string(scene.water.ru).substr(0, 5) + ")").c_str()
                    : scene.water.grid ? " (pressure grid)"
                                       : "");
    char second[300];
    std::snprintf(second, sizeof second, "%s%s",
                  scene.supports.empty() && scene.pointLoads.empty()
                      ? ""
                      : "supports: dark blue holding, magenta yielded, grey dashed slack or broken   arrows: loads   ",
                  water);
    cairo_move_to(cr, 20, height - 8);
    cairo_show_text(cr, second);
  }
  cairo_destroy(cr);
  // A temporary of this process's own: two commands drawing into one folder never share it.
  const std::string temporary = path + "." + std::to_string(::getpid()) + ".tmp";
  const cairo_status_t st = cairo_surface_write_to_png(surface, temporary.c_str());
  cairo_surface_destroy(surface);
  if (st != CAIRO_STATUS_SUCCESS || std::rename(temporary.c_str(), path.c_str()) != 0)
    throw InputError(path, "", "cannot write the picture");
}

}  // namespace ddaslope::io
