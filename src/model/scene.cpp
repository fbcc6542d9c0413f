#include "ddaslope/model/scene.hpp"

#include <algorithm>

namespace ddaslope::model {

int Scene::jointBetween(int a, int b) const {
  const auto it = pairJoints.find({std::min(a, b), std::max(a, b)});
  return it == pairJoints.end() ? defaultJoint : it->second;
}

int Scene::freeUnknowns() const {
  int free = 0;
  for (const Block& b : blocks) free += !b.fixed;
  return (settings.rigidBlocks ? 3 : 6) * free;
}

double Scene::modelHalfSize() const {
  geometry::Aabb box = geometry::boundingBox(blocks.front().vertices);
  for (const Block& b : blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    box.lo = box.lo.cwiseMin(bb.lo);
    box.hi = box.hi.cwiseMax(bb.hi);
  }
  return 0.5 * (box.hi - box.lo).maxCoeff();
}

double Scene::normalPenalty() const {
  if (settings.penalty > 0) return settings.penalty;
  double maxE = 0;
  for (const Material& m : materials) maxE = std::max(maxE, m.youngModulus);
  return settings.penaltyFactor * maxE;
}

int Scene::blockIndex(const std::string& id) const {
  for (size_t i = 0; i < blocks.size(); ++i)
    if (blocks[i].id == id) return static_cast<int>(i);
  return -1;
}

}  // namespace ddaslope::model
