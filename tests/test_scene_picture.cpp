// The scene pictures' framing (issue #43): a block on a large base is drawn zoomed on what can
// move, with the whole scene as an inset; a slope whose free blocks fill it is drawn whole.
#include <gtest/gtest.h>

#include "ddaslope/io/case_reader.hpp"
#include "ddaslope/io/scene_picture.hpp"

using namespace ddaslope;

namespace {

bool inside(const geometry::Aabb& box, const geometry::Aabb& in) {
  return in.lo.x() >= box.lo.x() && in.lo.y() >= box.lo.y() && in.hi.x() <= box.hi.x() && in.hi.y() <= box.hi.y();
}

}  // namespace

// cases/sliding_block_30deg.json: a 2 m × 1 m block on a 15 m incline (under 2 % of its box):
// zoomed, the view holding the block with room around it and lying within the whole scene.
// cases/toppling_slope.json: its columns cover a third of the scene: drawn whole with a 5 % margin.
TEST(ScenePicture, ZoomsOnFreeBlocksOnlyWhenTheyAreASmallPartOfTheScene) {
  const std::string dir = std::string(DDASLOPE_SOURCE_DIR) + "/cases/";
  const model::Scene block = io::readCase(dir + "sliding_block_30deg.json");
  const io::PictureFrame f = io::frameScene(block);
  EXPECT_TRUE(f.zoomed);
  for (const model::Block& b : block.blocks) {
    if (!b.fixed) {
      EXPECT_TRUE(inside(f.view, geometry::boundingBox(b.vertices)));
    }
  }
  EXPECT_TRUE(inside({f.whole.lo - 0.05 * (f.whole.hi - f.whole.lo), f.whole.hi + 0.05 * (f.whole.hi - f.whole.lo)},
                     f.view));
  const Vec2 v = f.view.hi - f.view.lo, w = f.whole.hi - f.whole.lo;
  EXPECT_LT(v.x() * v.y(), 0.25 * w.x() * w.y());
  const model::Scene slope = io::readCase(dir + "toppling_slope.json");
  const io::PictureFrame g = io::frameScene(slope);
  EXPECT_FALSE(g.zoomed);
  EXPECT_NEAR(g.view.lo.x(), g.whole.lo.x() - 0.05 * (g.whole.hi.x() - g.whole.lo.x()), 1e-9);
}
