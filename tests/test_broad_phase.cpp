// The broad phase (contact/broad_phase.hpp) against its definition: a pair of blocks is a
// candidate exactly when their boxes, each grown by the margin, overlap, unless both blocks are
// fixed. The grid must find that set, no pair twice, in (a, b) order, and the same set as the
// sweep it replaced, on scenes that strain a grid: a base block far larger than the cells, blocks
// in a long thin row, touching and coincident boxes, and boxes that are not finite.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ddaslope/contact/broad_phase.hpp"

using namespace ddaslope;

namespace {

std::vector<contact::BlockPair> allPairs(const std::vector<geometry::Aabb>& boxes, const std::vector<bool>& fixed,
                                         double m) {
  std::vector<contact::BlockPair> out;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j) {
      if (fixed[i] && fixed[j]) continue;
      const auto& p = boxes[i];
      const auto& q = boxes[j];
      const bool apart = q.lo.x() - m > p.hi.x() + m || p.lo.x() - m > q.hi.x() + m ||
                         q.lo.y() - m > p.hi.y() + m || p.lo.y() - m > q.hi.y() + m;
      if (!apart) out.push_back({i, j});
    }
  return out;
}

geometry::Aabb box(double x, double y, double w, double h) { return {{x, y}, {x + w, y + h}}; }

void expectDefinition(const std::vector<geometry::Aabb>& boxes, const std::vector<bool>& fixed, double m) {
  std::vector<int> order;
  const auto grid = contact::findCandidatePairs(boxes, fixed, m, order);
  std::vector<int> sweepOrder;
  const auto sweep = contact::sweepPairs(boxes, fixed, m, sweepOrder);
  const auto exact = allPairs(boxes, fixed, m);
  EXPECT_EQ(grid, exact);
  EXPECT_EQ(sweep, exact);
}

}  // namespace

TEST(BroadPhase, GridFindsExactlyTheOverlappingGrownBoxes) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(0, 1);
  for (int scene = 0; scene < 20; ++scene) {
    std::vector<geometry::Aabb> boxes;
    std::vector<bool> fixed;
    // A fixed base much larger than the blocks (it covers many cells).
    boxes.push_back(box(-5, -3, 60, 3));
    fixed.push_back(true);
    const int n = 50 + 40 * scene;
    for (int k = 0; k < n; ++k) {
      const double w = 0.2 + 1.5 * u(rng), h = 0.2 + 0.8 * u(rng);
      boxes.push_back(box(50 * u(rng), 20 * u(rng), w, h));
      fixed.push_back(u(rng) < 0.1);
    }
    // Touching (shared edges) and coincident boxes.
    boxes.push_back(box(10, 10, 1, 0.5));
    boxes.push_back(box(11, 10, 1, 0.5));
    boxes.push_back(box(11, 10, 1, 0.5));
    fixed.insert(fixed.end(), {false, false, false});
    expectDefinition(boxes, fixed, 0.01 * (scene % 4));
  }
}

TEST(BroadPhase, GridHandlesThinScenesAndNonFiniteBoxes) {
  // A row of 3000 bricks (a grid of 4 cells per block at most along one axis) and a pair far off.
  std::vector<geometry::Aabb> boxes;
  std::vector<bool> fixed;
  for (int k = 0; k < 3000; ++k) boxes.push_back(box(k * 1.0, 0, 1, 0.5)), fixed.push_back(false);
  boxes.push_back(box(1e6, 1e6, 1, 1));
  boxes.push_back(box(1e6 + 0.5, 1e6 + 0.5, 1, 1));
  fixed.insert(fixed.end(), {false, false});
  expectDefinition(boxes, fixed, 0.005);
  // A diverged block (its box not finite; the run stops after such a step): the sweep answers as
  // it did before the grid, and the finite blocks' pairs are all there.
  std::vector<geometry::Aabb> some(boxes.begin(), boxes.begin() + 10);
  std::vector<bool> someFixed(10, false);
  some.push_back({{NAN, 0}, {NAN, 1}});
  someFixed.push_back(false);
  std::vector<int> order, sweepOrder;
  const auto found = contact::findCandidatePairs(some, someFixed, 0.0, order);
  EXPECT_EQ(found, contact::sweepPairs(some, someFixed, 0.0, sweepOrder));
  std::vector<contact::BlockPair> finitePairs;
  for (const auto& p : found)
    if (p.b < 10) finitePairs.push_back(p);
  std::vector<geometry::Aabb> finite(some.begin(), some.begin() + 10);
  EXPECT_EQ(finitePairs, allPairs(finite, std::vector<bool>(10, false), 0.0));
  // None or one block: no pairs.
  EXPECT_TRUE(contact::findCandidatePairs({}, {}, 0.1, order).empty());
  EXPECT_TRUE(contact::findCandidatePairs({box(0, 0, 1, 1)}, {false}, 0.1, order).empty());
}
