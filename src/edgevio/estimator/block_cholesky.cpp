#include "edgevio/estimator/block_cholesky.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <vector>

namespace edgevio::estimator {

namespace {
constexpr int B = kStateBlock;
using Block = Eigen::Matrix<double, B, B>;
using BlockVec = Eigen::Matrix<double, B, 1>;
}  // namespace

namespace {

using Order = std::vector<long>;  // order[k]: the block placed at position k

/// first[k]: the first position whose block couples to the block at position k.
std::vector<long> envelope(const std::vector<std::vector<long>>& adjacency, const Order& order) {
  const long nb = static_cast<long>(order.size());
  std::vector<long> position(static_cast<std::size_t>(nb)), first(static_cast<std::size_t>(nb));
  for (long k = 0; k < nb; ++k) position[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = k;
  for (long k = 0; k < nb; ++k) {
    long f = k;
    for (long j : adjacency[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])])
      f = std::min(f, position[static_cast<std::size_t>(j)]);
    first[static_cast<std::size_t>(k)] = f;
  }
  return first;
}

/// Factorisation work of an envelope: Σ_k (k − f(k))² block products.
long envelopeCost(const std::vector<long>& first) {
  long c = 0;
  for (std::size_t k = 0; k < first.size(); ++k) c += (static_cast<long>(k) - first[k]) * (static_cast<long>(k) - first[k]);
  return c;
}

/// Reverse Cuthill-McKee (George & Liu §4.3): breadth-first from a block of
/// least degree, neighbours by increasing degree, reversed. It puts a hub (a
/// keyframe tracked by many frames) after its spokes, where it makes no fill.
Order reverseCuthillMcKee(const std::vector<std::vector<long>>& adjacency) {
  const long nb = static_cast<long>(adjacency.size());
  const auto degree = [&](long i) { return adjacency[static_cast<std::size_t>(i)].size(); };
  Order order;
  std::vector<bool> seen(static_cast<std::size_t>(nb), false);
  while (static_cast<long>(order.size()) < nb) {
    long start = -1;
    for (long i = 0; i < nb; ++i)
      if (!seen[static_cast<std::size_t>(i)] && (start < 0 || degree(i) < degree(start))) start = i;
    seen[static_cast<std::size_t>(start)] = true;
    std::size_t head = order.size();
    order.push_back(start);
    for (; head < order.size(); ++head) {
      std::vector<long> next;
      for (long j : adjacency[static_cast<std::size_t>(order[head])])
        if (!seen[static_cast<std::size_t>(j)]) {
          seen[static_cast<std::size_t>(j)] = true;
          next.push_back(j);
        }
      std::stable_sort(next.begin(), next.end(), [&](long a, long b) { return degree(a) < degree(b); });
      order.insert(order.end(), next.begin(), next.end());
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

/// Block (i, j) is nonzero: the blocks are coupled.
std::vector<std::vector<long>> blockAdjacency(const Eigen::MatrixXd& H) {
  const long nb = H.rows() / B;
  std::vector<std::vector<long>> adjacency(static_cast<std::size_t>(nb));
  for (long i = 0; i < nb; ++i)
    for (long j = 0; j < i; ++j)
      if ((H.block<B, B>(B * i, B * j).array() != 0.0).any()) {
        adjacency[static_cast<std::size_t>(i)].push_back(j);
        adjacency[static_cast<std::size_t>(j)].push_back(i);
      }
  return adjacency;
}

/// The cheapest of three orderings: time order, its reverse, and RCM; `first` its envelope.
Order cheapestOrder(const std::vector<std::vector<long>>& adjacency, std::vector<long>* first) {
  const long nb = static_cast<long>(adjacency.size());
  Order order(static_cast<std::size_t>(nb));
  for (long k = 0; k < nb; ++k) order[static_cast<std::size_t>(k)] = k;
  *first = envelope(adjacency, order);
  for (Order candidate : {Order(order.rbegin(), order.rend()), reverseCuthillMcKee(adjacency)}) {
    std::vector<long> f = envelope(adjacency, candidate);
    if (envelopeCost(f) < envelopeCost(*first)) {
      order = std::move(candidate);
      *first = std::move(f);
    }
  }
  return order;
}

/// The Cholesky factor L of H + λI inside the envelope of a block order. L
/// is kept row by row (positions k in `order`): row i is one 15 x
/// 15·(i − first[i] + 1) matrix holding blocks first[i] .. i side by side, so
/// that Σ_k L_ik L_jkᵀ is a single product with a long inner dimension (small
/// 15x15 products spend their time packing).
class EnvelopeFactor {
 public:
  EnvelopeFactor(Order order, std::vector<long> first)
      : order_(std::move(order)), first_(std::move(first)), L_(order_.size()) {}

 private:
  long firstOf(long i) const { return first_[static_cast<std::size_t>(i)]; }
  auto row(long i, long from, long count) { return L_[static_cast<std::size_t>(i)].middleCols(B * (from - firstOf(i)), B * count); }
  auto Lb(long i, long j) { return L_[static_cast<std::size_t>(i)].middleCols<B>(B * (j - firstOf(i))); }

 public:

  /// False when H + λI is not positive definite.
  bool factorize(const Eigen::MatrixXd& H, double lambda) {
    const long nb = static_cast<long>(order_.size());
    for (long i = 0; i < nb; ++i) {
      const long fi = firstOf(i);
      L_[static_cast<std::size_t>(i)].resize(B, B * (i - fi + 1));
      for (long j = fi; j <= i; ++j) {
        Block S = H.block<B, B>(B * order_[static_cast<std::size_t>(i)], B * order_[static_cast<std::size_t>(j)]);
        const long k0 = std::max(fi, firstOf(j));
        if (k0 < j) S.noalias() -= row(i, k0, j - k0) * row(j, k0, j - k0).transpose();
        if (j < i) {
          // L_ij L_jjᵀ = S
          Lb(i, j) = Lb(j, j).triangularView<Eigen::Lower>().solve(S.transpose()).transpose();
        } else {
          S.diagonal().array() += lambda;
          const Eigen::LLT<Block> llt(S);
          if (llt.info() != Eigen::Success) return false;
          Lb(i, i) = llt.matrixL();
        }
      }
    }
    return true;
  }

  /// L y = P rhs, then Lᵀ z = y (column-oriented, inside the envelope), x = Pᵀ z.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) {
    const long nb = static_cast<long>(order_.size());
    Eigen::VectorXd y(rhs.size());
    for (long k = 0; k < nb; ++k) y.segment<B>(B * k) = rhs.segment<B>(B * order_[static_cast<std::size_t>(k)]);
    for (long i = 0; i < nb; ++i) {
      const long fi = firstOf(i);
      BlockVec yi = y.segment<B>(B * i);
      if (fi < i) yi.noalias() -= row(i, fi, i - fi) * y.segment(B * fi, B * (i - fi));
      y.segment<B>(B * i) = Lb(i, i).triangularView<Eigen::Lower>().solve(yi);
    }
    for (long i = nb - 1; i >= 0; --i) {
      const BlockVec xi = Lb(i, i).transpose().triangularView<Eigen::Upper>().solve(BlockVec(y.segment<B>(B * i)));
      y.segment<B>(B * i) = xi;
      const long fi = firstOf(i);
      if (fi < i) y.segment(B * fi, B * (i - fi)).noalias() -= row(i, fi, i - fi).transpose() * xi;
    }
    Eigen::VectorXd x(rhs.size());
    for (long k = 0; k < nb; ++k) x.segment<B>(B * order_[static_cast<std::size_t>(k)]) = y.segment<B>(B * k);
    return x;
  }

 private:
  Order order_;
  std::vector<long> first_;
  std::vector<Eigen::Matrix<double, B, Eigen::Dynamic>> L_;
};

}  // namespace

bool solveEnvelopeCholesky(const Eigen::MatrixXd& H, double lambda, const Eigen::VectorXd& rhs, Eigen::VectorXd* x) {
  std::vector<long> first;
  Order order = cheapestOrder(blockAdjacency(H), &first);
  EnvelopeFactor factor(std::move(order), std::move(first));
  if (!factor.factorize(H, lambda)) return false;
  *x = factor.solve(rhs);
  return x->allFinite();
}

}  // namespace edgevio::estimator
