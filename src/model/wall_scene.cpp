#include "ddaslope/model/wall_scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace ddaslope::model {

namespace {

void addBlock(Scene& s, std::string id, bool fixed, std::vector<Vec2> vertices) {
  Block b;
  b.id = std::move(id);
  b.fixed = fixed;
  b.vertices = std::move(vertices);
  b.moments = geometry::computeMoments(b.vertices);
  s.blocks.push_back(std::move(b));
}

}  // namespace

Scene makeBrickWall(int n) {
  Scene s;
  s.description = "brick wall";
  s.materials.push_back({"rock", 2600, 10e9, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("joint", 35 * M_PI / 180, 0));
  const int perRow = std::max(2, static_cast<int>(std::lround(std::sqrt(2.0 * n))));
  const double bw = 2, bh = 1, width = perRow * bw;
  const auto add = [&](std::string id, bool fixed, std::vector<Vec2> v) { addBlock(s, std::move(id), fixed, std::move(v)); };
  add("base", true, {{-2, -2}, {width + 2, -2}, {width + 2, 0}, {-2, 0}});
  int made = 0;
  for (int r = 0; made < n; ++r) {
    const double y0 = r * bh;
    std::vector<std::pair<double, double>> spans;
    if (r % 2 == 0) {
      for (int k = 0; k < perRow; ++k) spans.emplace_back(k * bw, (k + 1) * bw);
    } else {
      spans.emplace_back(0, bw / 2);
      for (int k = 0; k + 1 < perRow; ++k) spans.emplace_back(bw / 2 + k * bw, bw / 2 + (k + 1) * bw);
      spans.emplace_back(width - bw / 2, width);
    }
    for (const auto& [x0, x1] : spans) {
      if (made == n) break;
      // Appended, not "b" + to_string(): GCC 12 warns falsely (-Wrestrict) on that operator+.
      std::string id = std::to_string(made++);
      id.insert(id.begin(), 'b');
      add(id, false, {{x0, y0}, {x1, y0}, {x1, y0 + bh}, {x0, y0 + bh}});
    }
  }
  s.settings.timeStep = 1e-3;
  s.settings.duration = 1e9;
  return s;
}

Scene makeAnchorWall(int rows, bool sudden) {
  Scene s;
  s.description = "side-by-side brick wall";
  s.materials.push_back({"rock", 2500, 1e10, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("joint", 30 * M_PI / 180, 0));
  const int columns = rows;
  const double bw = 1, bh = 0.5;
  const auto add = [&](std::string id, bool fixed, std::vector<Vec2> v) { addBlock(s, std::move(id), fixed, std::move(v)); };
  add("base", true, {{-1, -1}, {columns + 1.0, -1}, {columns + 1.0, 0}, {-1, 0}});
  for (int r = 0; r < rows; ++r) {
    const double y0 = r * bh, y1 = y0 + bh;
    std::vector<double> xs;
    if (r % 2 == 0) {
      for (int i = 0; i <= columns; ++i) xs.push_back(i * bw);
    } else {
      xs.push_back(0);
      for (int i = 0; i < columns; ++i) xs.push_back((i + 0.5) * bw);
      xs.push_back(columns * bw);
    }
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      std::string id = std::to_string(s.blocks.size());
      id.insert(id.begin(), 'b');
      add(id, false, {{xs[i], y0}, {xs[i + 1], y0}, {xs[i + 1], y1}, {xs[i], y1}});
    }
  }
  s.settings.timeStep = 1e-3;
  s.settings.duration = 1e9;
  s.settings.penalty = 1e11;
  s.settings.initialEquilibrium = !sudden;
  return s;
}

}  // namespace ddaslope::model
