// Property tests of SO(3) and SE(3) (in the spirit of Sophus' LieGroupTests):
// group identities, exp/log round trips, adjoints and Jacobians against
// numeric differentiation, at generic, near-zero and near-π angles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/test_support.h"
#include "edgevio/geometry/se3.h"

namespace edgevio::geometry {
namespace {


/// Rotation vectors covering generic, tiny and near-π angles.
std::vector<Vec3> testRotationVectors() {
  std::vector<Vec3> v = {Vec3::Zero(),
                         Vec3(1e-12, -2e-12, 0.5e-12),
                         Vec3(1e-7, 3e-7, -2e-7),
                         Vec3(2e-6, -1e-6, 4e-6),  // inside the Taylor branch
                         Vec3(3e-5, 1e-5, -2e-5),  // just outside it
                         Vec3(0.1, -0.2, 0.3),
                         Vec3(1.0, 0.5, -0.7),
                         Vec3(0.0, 0.0, kPi - 1e-6),
                         Vec3(kPi - 1e-9, 0.0, 0.0),
                         Vec3(1.0, 1.0, 1.0).normalized() * (kPi - 1e-4)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    Vec3 axis(u(rng), u(rng), u(rng));
    v.push_back(axis.normalized() * (kPi * std::abs(u(rng))));
  }
  return v;
}

std::vector<Vec6> testTwists() {
  std::vector<Vec6> out;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const Vec3& phi : testRotationVectors()) {
    Vec6 xi;
    xi << u(rng), u(rng), u(rng), phi;
    out.push_back(xi);
  }
  return out;
}

TEST(SO3, HatVeeAreInverseAndCrossProduct) {
  const Vec3 a(0.3, -1.2, 2.0), b(-0.7, 0.4, 1.1);
  EXPECT_LT((hat(a) * b - a.cross(b)).norm(), 1e-15);
  EXPECT_LT((vee(hat(a)) - a).norm(), 1e-15);
}

TEST(SO3, ExpLogRoundTrip) {
  for (const Vec3& phi : testRotationVectors()) {
    const SO3 R = SO3::exp(phi);
    // Norm invariant of the class.
    EXPECT_NEAR(R.quaternion().norm(), 1.0, 1e-12);
    // log is the inverse of exp for angles in [0, π).
    EXPECT_LT((R.log() - phi).norm(), 1e-9 * std::max(1.0, phi.norm())) << phi.transpose();
    // The matrix is a rotation.
    const Mat3 M = R.matrix();
    EXPECT_LT((M.transpose() * M - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(M.determinant(), 1.0, 1e-12);
  }
}

TEST(SO3, ExpMatchesRodriguesFormula) {
  for (const Vec3& phi : testRotationVectors()) {
    const double theta = phi.norm();
    if (theta < 1e-3) continue;
    const Mat3 K = hat(phi / theta);
    const Mat3 rodrigues = Mat3::Identity() + std::sin(theta) * K + (1.0 - std::cos(theta)) * K * K;
    EXPECT_LT((SO3::exp(phi).matrix() - rodrigues).norm(), 1e-12);
  }
}

TEST(SO3, LogAtExactlyPiGivesAnglePi) {
  const SO3 R = SO3::exp(Vec3(0.0, kPi, 0.0));
  EXPECT_NEAR(R.log().norm(), kPi, 1e-12);
  EXPECT_LT((SO3::exp(R.log()).matrix() - R.matrix()).norm(), 1e-12);
  // A rotation of π given as a matrix (quaternion with w = 0 up to rounding).
  Mat3 M = Vec3(1, 0, 0).asDiagonal();
  M(1, 1) = -1;
  M(2, 2) = -1;
  const SO3 Rm = SO3::fromMatrix(M);
  EXPECT_NEAR(Rm.log().norm(), kPi, 1e-12);
}

TEST(SO3, GroupAxioms) {
  const SO3 A = SO3::exp(Vec3(0.3, 0.2, -0.1)), B = SO3::exp(Vec3(-1.0, 0.4, 2.0)), C = SO3::exp(Vec3(0.0, 3.0, 0.1));
  EXPECT_LT(((A * B) * C).matrix().isApprox((A * (B * C)).matrix(), 1e-14) ? 0.0 : 1.0, 0.5);
  EXPECT_LT((A * A.inverse()).log().norm(), 1e-15);
  const Vec3 p(1.0, -2.0, 0.5);
  EXPECT_LT(((A * B) * p - A * (B * p)).norm(), 1e-14);
  EXPECT_LT((A * p - A.matrix() * p).norm(), 1e-14);
}

TEST(SO3, AdjointIdentity) {
  for (const Vec3& phi : testRotationVectors()) {
    const SO3 R = SO3::exp(phi);
    const Vec3 d(0.01, -0.02, 0.03);
    const SO3 lhs = R * SO3::exp(d) * R.inverse();
    EXPECT_LT((lhs.log() - R.adjoint() * d).norm(), 1e-12);
  }
}

TEST(SO3, JacobiansMatchNumericDifferentiation) {
  for (const Vec3& phi : testRotationVectors()) {
    if (phi.norm() > kPi - 1e-3) continue;  // log wraps at π: the finite differences straddle it
    // Right Jacobian: d/dδ log(exp(φ)⁻¹ exp(φ + δ)) at δ = 0.
    const auto right = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return (SO3::exp(phi).inverse() * SO3::exp(phi + Vec3(d))).log();
    };
    const auto left = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return (SO3::exp(phi + Vec3(d)) * SO3::exp(phi).inverse()).log();
    };
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
    test::expectJacobianNear(SO3::rightJacobian(phi), test::numericJacobian(right, zero), 1e-7, "Jr");
    test::expectJacobianNear(SO3::leftJacobian(phi), test::numericJacobian(left, zero), 1e-7, "Jl");
    // Inverse right Jacobian: d/dδ log(exp(φ) exp(δ)) at δ = 0.
    const auto logPerturbed = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return (SO3::exp(phi) * SO3::exp(Vec3(d))).log();
    };
    test::expectJacobianNear(SO3::rightJacobianInverse(phi), test::numericJacobian(logPerturbed, zero), 1e-6,
                             "Jr^-1");
    EXPECT_LT((SO3::leftJacobian(phi) * SO3::leftJacobianInverse(phi) - Mat3::Identity()).norm(), 1e-9);
    EXPECT_LT((SO3::rightJacobian(phi) * SO3::rightJacobianInverse(phi) - Mat3::Identity()).norm(), 1e-9);
  }
}

TEST(SO3, InverseJacobianFiniteNearPi) {
  const Vec3 phi(0.0, 0.0, kPi - 1e-9);
  EXPECT_TRUE(SO3::leftJacobianInverse(phi).allFinite());
  EXPECT_LT((SO3::leftJacobian(phi) * SO3::leftJacobianInverse(phi) - Mat3::Identity()).norm(), 1e-9);
}

TEST(SO3, InterpolationIsGeodesic) {
  const SO3 a = SO3::exp(Vec3(0.1, 0.2, 0.3)), b = SO3::exp(Vec3(-0.5, 1.0, 0.2));
  EXPECT_LT((interpolate(a, b, 0.0).log() - a.log()).norm(), 1e-12);
  EXPECT_LT((interpolate(a, b, 1.0).log() - b.log()).norm(), 1e-12);
  const double total = angle(a.inverse() * b);
  EXPECT_NEAR(angle(a.inverse() * interpolate(a, b, 0.25)), 0.25 * total, 1e-12);
  EXPECT_NEAR(angle(interpolate(a, b, 0.25).inverse() * b), 0.75 * total, 1e-12);
}

TEST(SO3, QuaternionHelpersUseFileOrders) {
  const Quat q = quaternionFromWxyz(0.5, 0.5, 0.5, 0.5);
  EXPECT_EQ(q.w(), 0.5);
  const Quat p = quaternionFromXyzw(0.1, 0.2, 0.3, 0.9);
  EXPECT_EQ(p.w(), 0.9);
  EXPECT_EQ(p.x(), 0.1);
}

TEST(SE3, ExpLogRoundTripAndGroupAxioms) {
  for (const Vec6& xi : testTwists()) {
    const SE3 T = SE3::exp(xi);
    EXPECT_LT((T.log() - xi).norm(), 1e-8 * std::max(1.0, xi.norm())) << xi.transpose();
    EXPECT_LT((T * T.inverse()).log().norm(), 1e-12);
    EXPECT_LT((T.matrix() * T.inverse().matrix() - Mat4::Identity()).norm(), 1e-12);
    const Vec3 p(0.4, -0.3, 2.0);
    EXPECT_LT((T * p - (T.matrix() * p.homogeneous()).head<3>()).norm(), 1e-12);
  }
}

TEST(SE3, ExpMatchesMatrixExponential) {
  // exp of the 4x4 twist matrix by a long Taylor series (converges for |ξ| of a few units).
  for (const Vec6& xi : testTwists()) {
    Mat4 X = Mat4::Zero();
    X.topLeftCorner<3, 3>() = hat(xi.tail<3>());
    X.topRightCorner<3, 1>() = xi.head<3>();
    Mat4 term = Mat4::Identity(), sum = Mat4::Identity();
    for (int k = 1; k < 60; ++k) {
      term = term * X / k;
      sum += term;
    }
    EXPECT_LT((SE3::exp(xi).matrix() - sum).norm(), 1e-10);
  }
}

TEST(SE3, AdjointIdentity) {
  for (const Vec6& xi : testTwists()) {
    const SE3 T = SE3::exp(xi);
    Vec6 d;
    d << 0.01, 0.02, -0.03, 0.004, -0.002, 0.003;
    const SE3 lhs = T * SE3::exp(d) * T.inverse();
    EXPECT_LT((lhs.log() - T.adjoint() * d).norm(), 1e-10);
  }
}

TEST(SE3, JacobiansMatchNumericDifferentiation) {
  for (const Vec6& xi : testTwists()) {
    if (xi.tail<3>().norm() > kPi - 1e-3) continue;  // log wraps at π
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
    const auto right = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return (SE3::exp(xi).inverse() * SE3::exp(xi + Vec6(d))).log();
    };
    const auto left = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return (SE3::exp(xi + Vec6(d)) * SE3::exp(xi).inverse()).log();
    };
    test::expectJacobianNear(SE3::rightJacobian(xi), test::numericJacobian(right, zero), 1e-6, "SE3 Jr");
    test::expectJacobianNear(SE3::leftJacobian(xi), test::numericJacobian(left, zero), 1e-6, "SE3 Jl");
    EXPECT_LT((SE3::leftJacobian(xi) * SE3::leftJacobianInverse(xi) - Mat6::Identity()).norm(), 1e-8);
    EXPECT_LT((SE3::rightJacobian(xi) * SE3::rightJacobianInverse(xi) - Mat6::Identity()).norm(), 1e-8);
  }
}

TEST(SE3, InterpolationEndpointsAndMidpoint) {
  const SE3 a(SO3::exp(Vec3(0.1, 0, 0)), Vec3(0, 0, 0)), b(SO3::exp(Vec3(0.3, 0, 0)), Vec3(2, 4, -2));
  const SE3 m = interpolate(a, b, 0.5);
  EXPECT_LT((m.translation() - Vec3(1, 2, -1)).norm(), 1e-15);
  EXPECT_LT((m.so3().log() - Vec3(0.2, 0, 0)).norm(), 1e-12);
  EXPECT_LT((interpolate(a, b, 1.0).matrix() - b.matrix()).norm(), 1e-12);
}

TEST(SE3, FromMatrixReorthonormalises) {
  Mat4 T = SE3::exp((Vec6() << 1, 2, 3, 0.3, -0.2, 0.1).finished()).matrix();
  T(0, 0) += 1e-6;  // a slightly non-orthonormal input, as printed calibration files are
  const SE3 S = SE3::fromMatrix(T);
  const Mat3 R = S.rotationMatrix();
  EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-12);
  EXPECT_LT((R - T.topLeftCorner<3, 3>()).norm(), 1e-5);
}

}  // namespace
}  // namespace edgevio::geometry
