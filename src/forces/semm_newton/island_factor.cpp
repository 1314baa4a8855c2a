#include "forces/semm_newton/island_factor.hpp"

namespace tem::newton {

void IslandFactor::set_pattern(int bodies, const std::vector<std::pair<int, int>>& pairs) {
  bodies_ = bodies;
  pairs_ = pairs;
  dense_ = bodies <= kDenseBodies;
  analysed_ = false;
}

bool IslandFactor::factorise(const std::vector<Mat6>& diagonal,
                             const std::vector<Mat6>& off_diagonal) {
  const int n = 6 * bodies_;
  if (dense_) {
    dense_matrix_.setZero(n, n);
    for (int b = 0; b < bodies_; ++b) dense_matrix_.block<6, 6>(6 * b, 6 * b) = diagonal[b];
    for (size_t k = 0; k < pairs_.size(); ++k) {
      const auto [i, j] = pairs_[k];
      dense_matrix_.block<6, 6>(6 * i, 6 * j) += off_diagonal[k];
      dense_matrix_.block<6, 6>(6 * j, 6 * i) += off_diagonal[k].transpose();
    }
    dense_factor_.compute(dense_matrix_);
    return dense_factor_.info() == Eigen::Success;
  }
  // Lower triangle: the diagonal blocks' lower halves and every pair's block (i > j). Explicit
  // zeros are kept, so that the pattern, and with it the symbolic analysis, stays the same.
  triplets_.clear();
  triplets_.reserve(static_cast<size_t>(21 * bodies_) + 36 * pairs_.size());
  for (int b = 0; b < bodies_; ++b)
    for (int c = 0; c < 6; ++c)
      for (int r = c; r < 6; ++r) triplets_.emplace_back(6 * b + r, 6 * b + c, diagonal[b](r, c));
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const auto [i, j] = pairs_[k];
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r)
        triplets_.emplace_back(6 * i + r, 6 * j + c, off_diagonal[k](r, c));
  }
  sparse_matrix_.resize(n, n);
  sparse_matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  if (!analysed_) {
    if (!sparse_factor_) sparse_factor_ = std::make_unique<SparseFactor>();
    sparse_factor_->analyzePattern(sparse_matrix_);
    analysed_ = true;
  }
  sparse_factor_->factorize(sparse_matrix_);
  return sparse_factor_->info() == Eigen::Success;
}

void IslandFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  x = dense_ ? Eigen::VectorXd(dense_factor_.solve(b)) : Eigen::VectorXd(sparse_factor_->solve(b));
}

}  // namespace tem::newton
