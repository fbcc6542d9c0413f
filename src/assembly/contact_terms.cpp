#include "ddaslope/assembly/contact_terms.hpp"

namespace ddaslope::assembly {

ContactKinematics linearise(const model::Block& vb, const model::Block& eb,
                            const contact::Contact& c) {
  const contact::ContactKey& k = c.key();
  const int n = static_cast<int>(eb.vertices.size());
  const Vec2 p1 = vb.vertices[k.vertex];
  const Vec2 p2 = eb.vertices[k.edge];
  const Vec2 p3 = eb.vertices[(k.edge + 1) % n];
  const double len = (p3 - p2).norm();
  ContactKinematics kin;
  kin.tangent = (p3 - p2) / len;
  // Penetration = Δ/l, Δ = cross(P2 − P1, P3 − P1) > 0 when P1 is inside the edge's block.
  kin.penetration0 = cross(p2 - p1, p3 - p1) / len + c.normalOffset;
  const Vec2 a1(p2.y() - p3.y(), p3.x() - p2.x());
  const Vec2 a2(p3.y() - p1.y(), p1.x() - p3.x());
  const Vec2 a3(p1.y() - p2.y(), p2.x() - p1.x());
  kin.normal.head<6>() = vb.tAt(p1).transpose() * a1 / len;
  kin.normal.tail<6>() = (eb.tAt(p2).transpose() * a2 + eb.tAt(p3).transpose() * a3) / len;
  // Shear: (P1 − P0)·t with P0 a material point of the edge, t fixed over the step.
  const Vec2& t = kin.tangent;
  const Vec2 anchor = p2 + c.lockRatio * (p3 - p2);
  const Vec2 start = p2 + c.geometry.ratio * (p3 - p2);
  kin.shearLocked0 = (p1 - anchor).dot(t);
  kin.shearLocked.head<6>() = vb.tAt(p1).transpose() * t;
  kin.shearLocked.tail<6>() = -eb.tAt(anchor).transpose() * t;
  kin.shearStep.head<6>() = kin.shearLocked.head<6>();
  kin.shearStep.tail<6>() = -eb.tAt(start).transpose() * t;
  return kin;
}

}  // namespace ddaslope::assembly
