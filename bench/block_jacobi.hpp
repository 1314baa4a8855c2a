// The bodies' 6 x 6 diagonal blocks of an island's Hessian, each inverted by its Cholesky
// factor: a preconditioner of conjugate gradients for the Newton step of SEMM by Newton
// (bench_island_factor.cpp), in the form Eigen's ConjugateGradient takes.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "tem/types.hpp"

namespace tem::bench {

class BlockJacobi {
 public:
  using Vec6 = Eigen::Matrix<Real, 6, 1>;
  using Mat6 = Eigen::Matrix<Real, 6, 6>;

  BlockJacobi() = default;
  template <class Matrix>
  explicit BlockJacobi(const Matrix& m) {
    compute(m);
  }
  template <class Matrix>
  BlockJacobi& analyzePattern(const Matrix&) {
    return *this;
  }
  template <class Matrix>
  BlockJacobi& factorize(const Matrix& m) {
    return compute(m);
  }
  // From a sparse matrix of 6 x 6 blocks (both triangles or the lower one).
  template <class Matrix>
  BlockJacobi& compute(const Matrix& m) {
    const Eigen::Index n = m.rows() / 6;
    blocks_.resize(static_cast<size_t>(n));
    for (Eigen::Index b = 0; b < n; ++b) {
      Mat6 block;
      for (int c = 0; c < 6; ++c)
        for (int r = c; r < 6; ++r) block(r, c) = block(c, r) = m.coeff(6 * b + r, 6 * b + c);
      blocks_[static_cast<size_t>(b)].compute(block);
    }
    return *this;
  }
  template <class Rhs>
  Eigen::Matrix<Real, Eigen::Dynamic, 1> solve(const Eigen::MatrixBase<Rhs>& b) const {
    Eigen::Matrix<Real, Eigen::Dynamic, 1> x(b.size());
    for (size_t k = 0; k < blocks_.size(); ++k) {
      const Eigen::Index at = static_cast<Eigen::Index>(6 * k);
      x.template segment<6>(at) = blocks_[k].solve(Vec6(b.template segment<6>(at)));
    }
    return x;
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  std::vector<Eigen::LLT<Mat6>> blocks_;
};

}  // namespace tem::bench
