#pragma once
// Basic numeric types shared by every layer.
#include <Eigen/Core>

namespace ddaslope {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
/// The six unknowns of a block (Shi 1988): u0, v0, r0, εx, εy, γxy about the centroid.
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
/// The unknowns of the two blocks of a contact, block i's six then block j's.
using Vec12 = Eigen::Matrix<double, 12, 1>;
/// Displacement matrix T(x, y): point displacement = T · D.
using Mat26 = Eigen::Matrix<double, 2, 6>;

constexpr double kPi = 3.14159265358979323846;
inline double degToRad(double deg) { return deg * kPi / 180.0; }
inline double radToDeg(double rad) { return rad * 180.0 / kPi; }

/// z-component of the 2-D cross product.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace ddaslope
