#include "ddaslope/assembly/contact_terms.hpp"

namespace ddaslope::assembly {

namespace {

// T(p)ᵀ·a without building the 2×6 matrix T (model::displacementMatrix) for each of the five
// uses per contact. The products by T's zeros and ones stay: they are the operations Eigen
// performs, and the signs of zeros they produce are kept with them.
Vec6 tTransposeTimes(const Vec2& centroid, const Vec2& p, const Vec2& a) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  Vec6 r;
  r[0] = 1.0 * a.x() + 0.0 * a.y();
  r[1] = 0.0 * a.x() + 1.0 * a.y();
  r[2] = -y * a.x() + x * a.y();
  r[3] = x * a.x() + 0.0 * a.y();
  r[4] = 0.0 * a.x() + y * a.y();
  r[5] = y / 2 * a.x() + x / 2 * a.y();
  return r;
}

// (−T(p))ᵀ·a, which Eigen evaluates with T's entries negated (not as −(Tᵀ·a): the sign of a
// zero sum would differ).
Vec6 minusTTransposeTimes(const Vec2& centroid, const Vec2& p, const Vec2& a) {
  const double x = p.x() - centroid.x(), y = p.y() - centroid.y();
  Vec6 r;
  r[0] = -1.0 * a.x() + -0.0 * a.y();
  r[1] = -0.0 * a.x() + -1.0 * a.y();
  r[2] = -(-y) * a.x() + -x * a.y();
  r[3] = -x * a.x() + -0.0 * a.y();
  r[4] = -0.0 * a.x() + -y * a.y();
  r[5] = -(y / 2) * a.x() + -(x / 2) * a.y();
  return r;
}

}  // namespace

ContactKinematics linearise(const model::Block& vb, const model::Block& eb,
                            const contact::Contact& c) {
  ContactKinematics kin;
  lineariseInto(vb, eb, c, kin);
  return kin;
}

void lineariseInto(const model::Block& vb, const model::Block& eb, const contact::Contact& c,
                   ContactKinematics& kin) {
  const contact::ContactKey& k = c.key();
  const int n = static_cast<int>(eb.vertices.size());
  const Vec2 p1 = vb.vertices[k.vertex];
  const Vec2 p2 = eb.vertices[k.edge];
  const Vec2 p3 = eb.vertices[(k.edge + 1) % n];
  const double len = (p3 - p2).norm();
  // Penetration = Δ/l, Δ = cross(P2 − P1, P3 − P1) > 0 when P1 is inside the edge's block.
  kin.penetration0 = cross(p2 - p1, p3 - p1) / len + c.normalOffset;
  const Vec2 a1(p2.y() - p3.y(), p3.x() - p2.x());
  const Vec2 a2(p3.y() - p1.y(), p1.x() - p3.x());
  const Vec2 a3(p1.y() - p2.y(), p2.x() - p1.x());
  const Vec2& vc = vb.moments.centroid;
  const Vec2& ec = eb.moments.centroid;
  kin.normal.head<6>() = tTransposeTimes(vc, p1, a1) / len;
  kin.normal.tail<6>() = (tTransposeTimes(ec, p2, a2) + tTransposeTimes(ec, p3, a3)) / len;
  // Shear: (P1 − P0)·t with P0 a material point of the edge, t fixed over the step.
  const Vec2 t = (p3 - p2) / len;
  const Vec2 anchor = p2 + c.lockRatio * (p3 - p2);
  const Vec2 start = p2 + c.geometry.ratio * (p3 - p2);
  kin.shearLocked0 = (p1 - anchor).dot(t);
  kin.shearLocked.head<6>() = tTransposeTimes(vc, p1, t);
  kin.shearLocked.tail<6>() = minusTTransposeTimes(ec, anchor, t);
  kin.shearStepEdge = minusTTransposeTimes(ec, start, t);
}

}  // namespace ddaslope::assembly
