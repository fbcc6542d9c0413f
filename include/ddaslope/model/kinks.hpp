#pragma once
// Concave kinks of a fixed block's surface under free blocks: where a block model and limit
// equilibrium of slices part ways (docs/calibration.md, "The chair-shaped slide").
#include <vector>

#include "ddaslope/core/types.hpp"
#include "ddaslope/model/scene.hpp"

namespace ddaslope::model {

struct ConcaveKink {
  int fixedBlock = 0;
  Vec2 point;             ///< the fixed block's vertex
  double bendDeg = 0;     ///< how far the surface turns up there (interior angle − 180°)
  /// How far up the slope (horizontally, towards the steeper side) the widest free block with a
  /// vertex there reaches (m): the lever of the corner force it can lean on.
  double upslopeReach = 0;
  double reachingBlockHeight = 0;  ///< that block's vertical extent (m)
  /// Free blocks with a vertex there: one is a block spanning the bend on a corner; two or more
  /// meet at a joint that ends on the bend (a joint of the slope, not an accident of the cut).
  int blocksWithCorner = 0;
};

/// Bends of 0.5° to 60° of a fixed block's surface (a sliding surface's kink, not a step of a
/// staircase) at which a free block has a vertex: a rigid or uniform-strain block there cannot
/// slide on along both sides without lifting, and can lean on the kink with a corner force that
/// slices cannot carry.
std::vector<ConcaveKink> concaveKinksUnderBlocks(const Scene& scene);

/// Moves each joint that ends on a concave kink of a fixed block's surface (one of the kinks
/// above) up the upper face by `offset` (m), at most a quarter of the edges it moves along. Such a
/// joint puts the corner of the block above in the notch, touching both faces: a uniform-strain
/// block cannot slide on along the upper face without lifting off it, and the force the corner
/// takes follows the contact stiffness (docs/research/bilinear-slab.md). Moved, the block below
/// owns the bend and can leave it along the lower face. Only where exactly two free blocks meet at
/// the kink across a joint inclined more than 10° from the vertical (gravity's direction): a
/// vertical joint there is a kink block's cut (docs/case-format.md, "Kink blocks"). The joint keeps
/// its direction when its other end lies on a straight outline of the two blocks alone, else it
/// turns about that end (then by at most 1/20 of its length). Returns what it moved.
std::vector<MovedJointEnd> moveJointEndsOffBends(Scene& scene, double offset);

/// Interior vertices of a sliding surface (crown to toe, x increasing) where it turns up (flatter
/// down the slope) by the same 0.5° to 60°.
std::vector<Vec2> concaveKinks(const std::vector<Vec2>& slidingSurface);

}  // namespace ddaslope::model
