// Conjugate gradients on an island's Hessian H = M + sum J^T G J given as its 6 x 6 blocks
// (island_factor.hpp), preconditioned by the bodies' diagonal blocks (block Jacobi): the linear
// solve of a Newton iteration on an island too large to factorise every iteration.
//
// Why: a resting pile's factor fills in with its separators (61 M entries, some 486 MB, for
// 10,000 coins) and costs about a second to compute, while on the same Hessian conjugate
// gradients with the bodies' blocks need about a hundred iterations whatever the pile's size
// (docs/benchmarks.md, "The island solve"). Started from zero, every iterate is a descent
// direction of the Newton objective, so an inexact solve only costs Newton iterations, never the
// exact line search's guarantee (island_factor.hpp, kIterativeAccuracy).
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "forces/semm_newton/newton_rows.hpp"

namespace tem::newton {

class BlockConjugateGradients {
 public:
  // The Hessian of `bodies` block rows: its diagonal blocks, and the block (i, j) of pair k,
  // pairs[k] = (i, j) with i > j, whose transpose is the block (j, i). Returns false if a
  // diagonal block is not positive definite (it always is in exact arithmetic: M is).
  bool prepare(int bodies, const std::vector<std::pair<int, int>>& pairs,
               const std::vector<Mat6>& diagonal, const std::vector<Mat6>& off_diagonal);
  // x with r = b - H x at most `accuracy` of b, both in the preconditioner's norm
  // (sqrt(r . P^-1 r), P the diagonal blocks), from x = 0, in at most `most` iterations.
  // Returns the iterations taken.
  int solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, Real accuracy, int most);

 private:
  int bodies_ = 0;
  std::vector<Eigen::LLT<Mat6>> diagonal_;  // each body's block, factorised
  std::vector<Mat6> diagonal_blocks_;
  // The off-diagonal blocks that are not zero, with their pairs: a pair whose rows are all
  // apart adds nothing.
  std::vector<std::pair<int, int>> pairs_;
  std::vector<Mat6> off_diagonal_;
  Eigen::VectorXd residual_, preconditioned_, direction_, product_;
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& out) const;
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
};

}  // namespace tem::newton
