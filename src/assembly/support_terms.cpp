#include "ddaslope/assembly/support_terms.hpp"

namespace ddaslope::assembly {

Vec12 supportElongationVector(const model::Support& s, const model::Block& head, const model::Block& end) {
  const Vec2 axis = s.end.current - s.head.current;
  const double length = axis.norm();
  // A support shortened to nothing has no direction: it carries nothing along one.
  if (!(length > 0)) return Vec12::Zero();
  const Vec2 n = axis / length;
  Vec12 v;
  v.head<6>() = -head.tAt(s.head.current).transpose() * n;
  v.tail<6>() = end.tAt(s.end.current).transpose() * n;
  return v;
}

}  // namespace ddaslope::assembly
