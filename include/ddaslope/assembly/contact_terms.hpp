#pragma once
// Linearised contact kinematics (Shi 1988, §2.5–2.6): pure functions of the geometry.
#include <Eigen/Core>

#include "ddaslope/contact/contact.hpp"
#include "ddaslope/model/block.hpp"

namespace ddaslope::assembly {

/// Penetration and shear of a vertex-to-edge contact as linear functions of [D_i; D_j]
/// (i: the vertex's block, j: the edge's block), evaluated on the geometry at the step start.
/// Kept once per contact and read several times a step (256 bytes: at 20 000 blocks 30 MB,
/// read from memory, not cache), so nothing in it is stored twice: the slip's vertex half is
/// the locked shear's.
struct ContactKinematics {
  Vec12 normal = Vec12::Zero();       ///< d penetration / d[D_i; D_j]
  Vec12 shearLocked = Vec12::Zero();  ///< d shear / d[D] relative to the lock anchor
  /// d slip / d D_j relative to the start-of-step projection (d slip / d D_i = shearLocked's).
  Vec6 shearStepEdge = Vec6::Zero();
  double penetration0 = 0;   ///< penetration before the step (m), > 0 overlapping
  double shearLocked0 = 0;   ///< shear spring elongation before the step (m)
  /// d slip / d[D_i; D_j] relative to the start-of-step projection.
  Vec12 shearStep() const {
    Vec12 v;
    v << shearLocked.head<6>(), shearStepEdge;
    return v;
  }
  double penetration(const Vec12& d) const { return penetration0 + normal.dot(d); }
  double shearFromAnchor(const Vec12& d) const { return shearLocked0 + shearLocked.dot(d); }
  double slip(const Vec12& d) const { return shearStep().dot(d); }
};
// Four cache lines, no padding: the 12-vectors first, the scalars last (a scalar between two
// vectors would pad the record to their alignment).
static_assert(sizeof(ContactKinematics) == 256, "ContactKinematics grew: it is read several times a step");

/// Δ = det[1 x1 y1; 1 x2 y2; 1 x3 y3] / l with the second-order term dropped (Shi eq. 2.52).
ContactKinematics linearise(const model::Block& vertexBlock, const model::Block& edgeBlock,
                            const contact::Contact& c);
/// The same, written over every field of `out`: a step's kinematics (a few MB at 2000 bricks)
/// are refreshed in place, without a zeroed temporary per contact copied into them.
void lineariseInto(const model::Block& vertexBlock, const model::Block& edgeBlock, const contact::Contact& c,
                   ContactKinematics& out);

}  // namespace ddaslope::assembly
