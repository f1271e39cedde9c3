#pragma once
// Cholesky factorisation of the window's normal equations that exploits
// their structure (METHOD.md §5). With the states in time order, inertial
// links and the prior left by marginalisation couple neighbours, and a
// tracking link couples a keyframe to the frames tracked against it, which
// follow it in the window: every nonzero 15x15 block (i, j), j ≤ i, lies in a
// variable band j ≥ f(i). Cholesky creates no fill outside that envelope
// (George & Liu, "Computer Solution of Large Sparse Positive Definite
// Systems", §4), so factorising costs Σ_i (i − f(i))² block products instead
// of the dense (15N)³/3; a loop-closure link only widens the rows it touches.
// A keyframe tracked by many later frames is a hub that would fill every row
// after it, so the blocks are reordered first: the cheapest envelope of time
// order, reverse time order and reverse Cuthill-McKee (George & Liu §4.3).
#include <Eigen/Core>

namespace edgevio::estimator {

/// The state dimension the blocks have.
inline constexpr int kStateBlock = 15;

/// Solves (H + λI)·x = rhs for symmetric H of 15x15 blocks, reading only the
/// lower triangle's nonzero blocks (exact zeros are structure). Returns false
/// when H + λI is not positive definite (x is then unspecified).
bool solveEnvelopeCholesky(const Eigen::MatrixXd& H, double lambda, const Eigen::VectorXd& rhs, Eigen::VectorXd* x);

}  // namespace edgevio::estimator
