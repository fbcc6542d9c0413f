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
  f.view = geometry::boundingBox(scene.blocks.front().vertices);
  for (const model::Block& b : scene.blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    f.view.lo = f.view.lo.cwiseMin(bb.lo);
    f.view.hi = f.view.hi.cwiseMax(bb.hi);
    f.initialCentroids.push_back(b.moments.centroid);
  }
  const Vec2 margin = 0.05 * (f.view.hi - f.view.lo);
  f.view.lo -= margin;
  f.view.hi += margin;
  return f;
}

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
                       const std::string& title) {
  const model::Scene& scene = state.scene;
  const double worldW = frame.view.hi.x() - frame.view.lo.x(), worldH = frame.view.hi.y() - frame.view.lo.y();
  const int width = 1000, top = 40, bottom = 50;
  const double scale = (width - 40) / worldW;
  const int height = static_cast<int>(worldH * scale) + top + bottom;
  const auto px = [&](const Vec2& p) {
    return std::pair{20 + (p.x() - frame.view.lo.x()) * scale, top + (frame.view.hi.y() - p.y()) * scale};
  };
  std::vector<double> moved(scene.blocks.size(), 0);
  double maxMoved = 0;
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    moved[b] = (scene.blocks[b].moments.centroid - frame.initialCentroids[b]).norm();
    if (!scene.blocks[b].fixed) maxMoved = std::max(maxMoved, moved[b]);
  }
  const auto ramp = [](double t, double* c) {  // blue (still) → yellow → red (moved most)
    const double k[3][3] = {{0.35, 0.55, 0.85}, {0.98, 0.85, 0.30}, {0.85, 0.20, 0.15}};
    t = std::clamp(t, 0.0, 1.0) * 2;
    const int i = std::min(1, static_cast<int>(t));
    for (int a = 0; a < 3; ++a) c[a] = k[i][a] + (k[i + 1][a] - k[i][a]) * (t - i);
  };
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  // Water below the phreatic line (a pore-pressure ratio or a pressure grid has no free water to
  // draw: the legend names it).
  if (scene.water.active() && scene.water.ru <= 0 && !scene.water.grid) {
    cairo_set_source_rgba(cr, 0.55, 0.75, 0.95, 0.5);
    const int steps = 200;
    for (int i = 0; i <= steps; ++i) {
      const double x = frame.view.lo.x() + worldW * i / steps;
      const auto [sx, sy] = px({x, std::min(scene.water.headAt(x), frame.view.hi.y())});
      i == 0 ? cairo_move_to(cr, sx, sy) : cairo_line_to(cr, sx, sy);
    }
    const auto [rx, ry] = px({frame.view.hi.x(), frame.view.lo.y()});
    const auto [lx, ly] = px(frame.view.lo);
    cairo_line_to(cr, rx, ry);
    cairo_line_to(cr, lx, ly);
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  // Blocks.
  cairo_set_line_width(cr, 1.2);
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    const model::Block& blk = scene.blocks[b];
    for (size_t k = 0; k < blk.vertices.size(); ++k) {
      const auto [x, y] = px(blk.vertices[k]);
      k == 0 ? cairo_move_to(cr, x, y) : cairo_line_to(cr, x, y);
    }
    cairo_close_path(cr);
    double c[3] = {0.78, 0.78, 0.78};
    if (!blk.fixed) ramp(maxMoved > 0 ? moved[b] / maxMoved : 0, c);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
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
  if (maxMoved > 0) {
    cairo_set_source_rgb(cr, 0.35, 0.0, 0.25);
    cairo_set_line_width(cr, 1.5);
    for (size_t b = 0; b < scene.blocks.size(); ++b) {
      if (scene.blocks[b].fixed || moved[b] < 0.05 * maxMoved) continue;
      const Vec2 d = (scene.blocks[b].moments.centroid - frame.initialCentroids[b]) / maxMoved;
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
  for (const model::Monitor& m : scene.monitors) {
    const auto [x, y] = px(m.point.current);
    cairo_move_to(cr, x - 5, y - 5);
    cairo_line_to(cr, x + 5, y + 5);
    cairo_move_to(cr, x - 5, y + 5);
    cairo_line_to(cr, x + 5, y - 5);
    cairo_stroke(cr);
  }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 15);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_move_to(cr, 20, 26);
  cairo_show_text(cr, title.c_str());
  char legend[300];
  std::snprintf(legend, sizeof legend,
                "t = %.4g s   colour and purple arrows: block displacement, blue 0 to red %.3g m (longest arrow)   "
                "contacts: green locked, orange sliding   x: monitors",
                state.time, maxMoved);
  cairo_set_font_size(cr, 12);
  cairo_move_to(cr, 20, height - 18);
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
    cairo_move_to(cr, 20, height - 4);
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
