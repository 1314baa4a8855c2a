#include "forces/semm_newton/block_conjugate_gradients.hpp"

#include <cmath>

namespace tem::newton {

bool BlockConjugateGradients::prepare(int bodies, const std::vector<std::pair<int, int>>& pairs,
                                      const std::vector<Mat6>& diagonal,
                                      const std::vector<Mat6>& off_diagonal) {
  bodies_ = bodies;
  diagonal_blocks_ = diagonal;
  diagonal_.resize(static_cast<size_t>(bodies));
  for (int b = 0; b < bodies; ++b) {
    diagonal_[b].compute(diagonal[b]);
    if (diagonal_[b].info() != Eigen::Success) return false;
  }
  pairs_.clear();
  off_diagonal_.clear();
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (off_diagonal[k].isZero(0)) continue;
    pairs_.push_back(pairs[k]);
    off_diagonal_.push_back(off_diagonal[k]);
  }
  return true;
}

void BlockConjugateGradients::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
  out.resize(x.size());
  for (int b = 0; b < bodies_; ++b)
    out.segment<6>(6 * b) = diagonal_blocks_[b] * x.segment<6>(6 * b);
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const int i = 6 * pairs_[k].first, j = 6 * pairs_[k].second;
    out.segment<6>(i) += off_diagonal_[k] * x.segment<6>(j);
    out.segment<6>(j) += off_diagonal_[k].transpose() * x.segment<6>(i);
  }
}

void BlockConjugateGradients::precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  z.resize(r.size());
  for (int b = 0; b < bodies_; ++b)
    z.segment<6>(6 * b) = diagonal_[b].solve(Vec6(r.segment<6>(6 * b)));
}

int BlockConjugateGradients::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, Real accuracy,
                                   int most) {
  x.setZero(b.size());
  residual_ = b;
  precondition(residual_, preconditioned_);
  Real rz = residual_.dot(preconditioned_);
  const Real enough = accuracy * accuracy * rz;
  direction_ = preconditioned_;
  int k = 0;
  while (k < most && rz > enough) {
    multiply(direction_, product_);
    const Real curvature = direction_.dot(product_);
    if (!(curvature > 0)) break;  // round-off: nothing more to gain along any direction
    const Real step = rz / curvature;
    x += step * direction_;
    residual_ -= step * product_;
    precondition(residual_, preconditioned_);
    const Real next = residual_.dot(preconditioned_);
    direction_ = preconditioned_ + (next / rz) * direction_;
    rz = next;
    ++k;
  }
  return k;
}

}  // namespace tem::newton
