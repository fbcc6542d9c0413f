#pragma once
// What the case reader makes of the blocks as drawn, so that the same slope gives the same answer
// however it is written (docs/contact-model.md, "One face, one contact"): fixed blocks drawn in
// pieces merged, vertices on straight edges removed, joints ending on a concave bend moved off it,
// a scene far from the origin computed next to it.
#include "ddaslope/model/scene.hpp"

namespace ddaslope::io {

/// Fixed blocks that share a stretch of boundary and meet every other block with the same joint
/// become one (monitors, loads and fixed points follow).
void mergeFixedBlocks(model::Scene& s);
/// Removes vertices on straight edges (within kCollinearTolerance of the chord, or within the gap
/// that counts as touching).
void normaliseOutlines(model::Scene& s);
/// Moves joints that end on a concave bend of a fixed block up its upper face
/// (analysis.joint_end_offset; model/kinks.hpp).
void moveJointEndsOffBends(model::Scene& s);
/// Holds a scene far from (0, 0) against its size relative to model::Scene::origin.
void localiseOrigin(model::Scene& s);

}  // namespace ddaslope::io
