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

}  // namespace edgevio
