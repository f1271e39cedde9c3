#pragma once
// Fixed-size Eigen aliases used throughout edgevio. All maths is in double.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace edgevio {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat4 = Eigen::Matrix4d;
using Quat = Eigen::Quaterniond;  // Hamilton convention (Eigen's), w-first storage order is irrelevant.

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace edgevio
