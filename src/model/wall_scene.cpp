#include "ddaslope/model/wall_scene.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace ddaslope::model {

Scene makeBrickWall(int n) {
  Scene s;
  s.description = "brick wall";
  s.materials.push_back({"rock", 2600, 10e9, 0.25});
  s.joints.push_back(model::JointProperties::coulomb("joint", 35 * M_PI / 180, 0));
  const int perRow = std::max(2, static_cast<int>(std::lround(std::sqrt(2.0 * n))));
  const double bw = 2, bh = 1, width = perRow * bw;
  const auto add = [&](std::string id, bool fixed, std::vector<Vec2> v) {
    Block b;
    b.id = std::move(id);
    b.fixed = fixed;
    b.vertices = std::move(v);
    b.moments = geometry::computeMoments(b.vertices);
    s.blocks.push_back(b);
  };
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

}  // namespace ddaslope::model
