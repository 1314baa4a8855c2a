// The linear solve of one Newton iteration (semm_newton.hpp): H dy = -g for an island's
// Hessian H = M + sum J^T G J, a symmetric positive definite matrix of 6 x 6 blocks, one block
// row per body, an off-diagonal block per pair of bodies in contact.
//
// Why a direct factorisation: it is what makes the weight of the top grain reach the floor in
// one iteration, whatever the height of the pile (a Gauss-Seidel sweep carries it one layer).
// Small islands (at most kDenseBodies bodies: a grain on the floor, a few touching) take a dense
// Cholesky factorisation; larger ones Eigen's sparse Cholesky (SimplicialLDLT with an approximate
// minimum degree ordering), whose symbolic analysis is made once per step and reused by every
// iteration of the step (the pattern holds every row, pushing or not). Measured beside it
// (docs/benchmarks.md, "The island solve"): CHOLMOD's supernodal factorisation is faster from
// 1,000 bodies on, and conjugate gradients preconditioned by the bodies' blocks faster still on
// a resting pile, but slower than this factorisation in a pour's crash.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <memory>
#include <utility>
#include <vector>

#include "forces/semm_newton/newton_rows.hpp"

namespace tem::newton {

inline constexpr int kDenseBodies = 8;

class IslandFactor {
 public:
  IslandFactor() = default;
  // A copy (of a workspace) keeps the pattern and factorises afresh: Eigen's factors are not
  // copied.
  IslandFactor(const IslandFactor& other) { *this = other; }
  IslandFactor& operator=(const IslandFactor& other) {
    if (this != &other) set_pattern(other.bodies_, other.pairs_);
    return *this;
  }
  IslandFactor(IslandFactor&&) = default;
  IslandFactor& operator=(IslandFactor&&) = default;

  // The island's pattern: `bodies` block rows, and the pairs (i > j) of bodies that share a row.
  void set_pattern(int bodies, const std::vector<std::pair<int, int>>& pairs);
  // Blocks of H: the diagonal ones, one per body, and one per pair in set_pattern's order.
  // Returns false if H is not positive definite (it always is in exact arithmetic: M is).
  bool factorise(const std::vector<Mat6>& diagonal, const std::vector<Mat6>& off_diagonal);
  // x = H^-1 b.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  int bodies_ = 0;
  std::vector<std::pair<int, int>> pairs_;
  bool dense_ = true;
  bool analysed_ = false;
  Eigen::MatrixXd dense_matrix_;
  Eigen::LLT<Eigen::MatrixXd> dense_factor_;
  std::vector<Eigen::Triplet<Real>> triplets_;
  Eigen::SparseMatrix<Real> sparse_matrix_;
  using SparseFactor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>, Eigen::Lower>;
  std::unique_ptr<SparseFactor> sparse_factor_;
};

}  // namespace tem::newton
