// The envelope Cholesky must solve exactly what a dense Cholesky solves, for
// any envelope: a chain, a chain with keyframe links, a loop link, a full matrix.
#include "edgevio/estimator/block_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <utility>
#include <vector>

#include "edgevio/sim/random.h"

namespace edgevio::estimator {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// A symmetric positive definite matrix whose nonzero off-diagonal blocks are `links`.
MatrixXd structuredSpd(long nb, const std::vector<std::pair<long, long>>& links, sim::Rng& rng) {
  const long B = kStateBlock;
  MatrixXd H = MatrixXd::Zero(B * nb, B * nb);
  const auto randomBlock = [&](long r, long c) {
    MatrixXd m(r, c);
    for (long i = 0; i < r; ++i)
      for (long j = 0; j < c; ++j) m(i, j) = rng.gaussian();
    return m;
  };
  for (const auto& [i, j] : links) {
    // Each link is a factor JᵀJ over its two states: positive semidefinite.
    const MatrixXd J = randomBlock(6, 2 * B);
    const MatrixXd JtJ = J.transpose() * J;
    const long idx[2] = {i, j};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) H.block(B * idx[a], B * idx[b], B, B) += JtJ.block(B * a, B * b, B, B);
  }
  for (long i = 0; i < nb; ++i) {
    const MatrixXd A = randomBlock(B, B);
    H.block(B * i, B * i, B, B) += A * A.transpose() + MatrixXd::Identity(B, B);
  }
  return H;
}

void expectSameAsDense(const MatrixXd& H, sim::Rng& rng, const char* what) {
  VectorXd rhs(H.rows());
  for (long i = 0; i < rhs.size(); ++i) rhs(i) = rng.gaussian();
  const double lambda = 1e-3;
  const VectorXd dense = (H + lambda * MatrixXd::Identity(H.rows(), H.cols())).llt().solve(rhs);
  VectorXd x;
  ASSERT_TRUE(solveEnvelopeCholesky(H, lambda, rhs, &x)) << what;
  // Both are backward stable; their difference is bounded by cond(H)·ε·‖x‖.
  const double cond_bound = 1e-12 * 1e4;
  EXPECT_LT((x - dense).norm(), cond_bound * dense.norm()) << what;
}

TEST(EnvelopeCholesky, MatchesDenseCholeskyOnWindowStructures) {
  sim::Rng rng(17);
  const long n = 30;
  std::vector<std::pair<long, long>> chain;
  for (long i = 0; i + 1 < n; ++i) chain.emplace_back(i, i + 1);
  expectSameAsDense(structuredSpd(n, chain, rng), rng, "chain");

  auto keyframes = chain;
  for (long k = 0; k < n; k += 6)
    for (long j = k + 1; j < std::min(n, k + 6); ++j) keyframes.emplace_back(k, j);
  expectSameAsDense(structuredSpd(n, keyframes, rng), rng, "keyframe links");

  auto loop = keyframes;
  loop.emplace_back(2, 27);
  expectSameAsDense(structuredSpd(n, loop, rng), rng, "loop link");

  std::vector<std::pair<long, long>> full;
  for (long i = 0; i < 8; ++i)
    for (long j = i + 1; j < 8; ++j) full.emplace_back(i, j);
  expectSameAsDense(structuredSpd(8, full, rng), rng, "full");
}

TEST(EnvelopeCholesky, ReportsIndefiniteMatrices) {
  sim::Rng rng(5);
  MatrixXd H = structuredSpd(4, {{0, 1}, {1, 2}, {2, 3}}, rng);
  H(20, 20) = -1e6;
  VectorXd x;
  EXPECT_FALSE(solveEnvelopeCholesky(H, 0.0, VectorXd::Ones(H.rows()), &x));
  // A large enough perturbation makes it definite again (the perturbed Cholesky of METHOD.md §5).
  EXPECT_TRUE(solveEnvelopeCholesky(H, 2e6, VectorXd::Ones(H.rows()), &x));
}

}  // namespace
}  // namespace edgevio::estimator
