// The linear solve of one Newton iteration (semm_newton.hpp): H dy = -g for an island's
// Hessian H = M + sum J^T G J, a symmetric positive definite matrix of 6 x 6 blocks, one block
// row per body, an off-diagonal block per pair of bodies in contact.
//
// Why a direct factorisation: it is what makes the weight of the top grain reach the floor in
// one iteration, whatever the height of the pile (a Gauss-Seidel sweep carries it one layer).
// Three factorisations, by the island's size and shape:
//   - at most kDenseBodies bodies (a grain on the floor, a few touching): a dense Cholesky;
//   - larger: Eigen's sparse Cholesky (SimplicialLDLT), column by column, where the factor is
//     sparse: chains and the loose clusters of a pour;
//   - CHOLMOD's supernodal Cholesky (SuiteSparse) where the factorisation takes at least
//     kSupernodalFlopsPerEntry flops per entry of the factor (a column of c entries below the
//     diagonal costs c^2): a pile, whose separators are dense blocks of hundreds of unknowns,
//     and a pour's large islands. It gathers columns of one pattern into dense blocks and
//     factorises them with BLAS. CHOLMOD chooses between its own two factorisations by the
//     same ratio and bound. Measured on every matrix of real runs (docs/benchmarks.md, "The
//     island solve"): the rule takes 9 % off the factorisations of a 1,000-coin pour's crash
//     against the one before it (40 entries a column on average), within 1 % of choosing the
//     faster for each matrix, and leaves 100-coin pours and columns as they were.
// The factor's pattern holds only the pairs whose block has been non-zero in this step's
// iterations: a pair whose rows are all apart (found within the contact margin, not pushing)
// adds nothing to H, and left out, a pour's island falls apart into the clusters that push on
// each other. In a 1,000-coin pour's crash a third of the pairs push and the largest cluster
// holds a third to a half of the island's bodies; the crash's first 0.06 s takes 40 % less time
// than with every pair in the pattern (docs/benchmarks.md, "The factor's pattern: only the pairs
// that push"). A pair once seen pushing stays for the step, so that the pattern holds while the
// active set settles.
// Both sparse factorisations take the matrix in an order of the bodies chosen by approximate
// minimum degree on the graph of the bodies and their live pairs (order_bodies): Eigen's own
// ordering of the 6 N unknowns, and its permutation of the matrix in every factorisation, took
// 7-12 % more time in pours (docs/benchmarks.md, "The factor's pattern: only the pairs that
// push"). CHOLMOD, given the same matrix, still orders it its own way and permutes it in every
// factorisation (cholmod_transpose_sym, 3-4 % of a crash's or a drum's samples): work done
// twice, left so far because its order fills in differently and would change the bits.
// Eigen's symbolic analysis, which counts the entries of the factor's columns, is made
// once per pattern and decides; the analysis of the chosen factorisation is reused by every
// iteration while no pair joins the pattern, and by the next steps while the island's contact
// graph and the pairs that push stay the same (a resting island). The pattern depends only on
// the step's own iterates, so it and the choice are the same at any thread count and across a
// resume (a resumed run's fresh factor makes the same); so that the BLAS gives the same bits
// too, it is held to one thread (island_factor.cpp). Measured beside these: conjugate gradients
// preconditioned by the step's earlier factor were slower everywhere (docs/benchmarks.md).
//
// Where the factor fills in (the supernodal choice) on an island of at least kIterativeBodies
// bodies, the solve is conjugate gradients instead, preconditioned by the bodies' 6 x 6 blocks
// and stopped at kIterativeAccuracy (block_conjugate_gradients.hpp): an inexact Newton step,
// which costs a few more Newton iterations but no factorisation. Measured in whole runs
// (docs/benchmarks.md, "Conjugate gradients for large islands"): the silo's 2,000-grain island
// 2.5-2.7 times faster, the 1,000-coin pour's crash 1.4 times, a 10,000-coin pile 3.4 times, a
// settled 1,000-coin pile within the machine's spread; forced on columns (chains, whose factor
// does not fill in: never chosen there) seven times slower. Solved to 1e-8 instead, conjugate
// gradients lost in a pour's crash: the accuracy asked is what pays.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <memory>
#include <utility>
#include <vector>

#include "forces/semm_newton/block_conjugate_gradients.hpp"
#include "forces/semm_newton/newton_rows.hpp"

namespace tem::newton {

inline constexpr int kDenseBodies = 8;
// Conjugate gradients: on an island of at least kIterativeBodies bodies whose factor would fill
// in; each solve to kIterativeAccuracy of its right-hand side, in at most kMostIterations.
// Why 1e-2: at 1e-1 a 10,000-coin pile's sub-steps took twice the Newton iterations, at 3e-1
// none converged in the budget, and asked for the accuracy the stopping rule needs (down to
// 1e-12) the solves took five times the conjugate-gradient iterations (docs/benchmarks.md).
inline constexpr int kIterativeBodies = 500;
inline constexpr Real kIterativeAccuracy = 1e-2;
inline constexpr int kMostIterations = 1000;
inline constexpr double kSupernodalFlopsPerEntry = 40;

class IslandFactor {
 public:
  // Defined beside SupernodalFactor (island_factor.cpp), which is complete only there.
  IslandFactor();
  // A copy (of a workspace) keeps the pattern and factorises afresh: the factors are not copied.
  IslandFactor(const IslandFactor& other);
  IslandFactor& operator=(const IslandFactor& other);
  IslandFactor(IslandFactor&&) noexcept;
  IslandFactor& operator=(IslandFactor&&) noexcept;
  ~IslandFactor();

  // The island's contact graph: `bodies` block rows, and the pairs (i > j) of bodies that share
  // a row.
  void set_pattern(int bodies, const std::vector<std::pair<int, int>>& pairs);
  // Blocks of H: the diagonal ones, one per body, and one per pair in set_pattern's order.
  // Returns false if H is not positive definite (it always is in exact arithmetic: M is).
  bool factorise(const std::vector<Mat6>& diagonal, const std::vector<Mat6>& off_diagonal);
  // x = H^-1 b; by conjugate gradients, to kIterativeAccuracy (block_conjugate_gradients.hpp).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Whether this step's factorisation is CHOLMOD's supernodal one (known once factorised).
  bool supernodal() const { return kind_ == Kind::supernodal; }
  // Whether this step's solves are conjugate gradients' instead (known once factorised).
  bool iterative() const { return kind_ == Kind::iterative; }
  // How many symbolic analyses this factor has made: one per new pattern.
  int analyses() const { return analyses_; }

 private:
  int bodies_ = 0;
  std::vector<std::pair<int, int>> pairs_;
  // Per pair: whether its block has been non-zero in a factorisation since the last
  // set_pattern (this step's iterations); only those pairs are in the factor's pattern, which
  // so depends on this step alone (a resumed run's fresh factor has the same), and those of
  // the pattern the analysis was made for.
  std::vector<char> live_, analysed_live_;
  // Marks the pairs whose block is non-zero now; a pattern other than the analysed one is
  // analysed afresh.
  void mark_live(const std::vector<Mat6>& off_diagonal);
  enum class Kind { dense, simplicial, supernodal, iterative };
  Kind kind_ = Kind::dense;
  bool analysed_ = false;
  int analyses_ = 0;
  Eigen::MatrixXd dense_matrix_;
  Eigen::LLT<Eigen::MatrixXd> dense_factor_;
  Eigen::SparseMatrix<Real> sparse_matrix_;  // upper triangle, compressed
  std::vector<Eigen::Index> value_index_;    // where each entry lands in its values
  // The factor's order of the bodies: body b's unknowns are rows 6 position_[b] to +5. Chosen
  // by approximate minimum degree on the graph of the bodies and their live pairs, once per
  // pattern.
  std::vector<int> position_;
  Eigen::VectorXd ordered_, answer_;  // solve's right-hand side and answer in the factor's order
  void order_bodies();
  struct SimplicialFactor;  // Eigen's, with the count of its factor's entries
  struct SupernodalFactor;  // CHOLMOD's, defined where its header is included: the .cpp
  std::unique_ptr<SimplicialFactor> simplicial_factor_;
  std::unique_ptr<SupernodalFactor> supernodal_factor_;
  BlockConjugateGradients conjugate_gradients_;
  bool iterative_this_step_ = false;  // conjugate gradients chosen since the last set_pattern
};

}  // namespace tem::newton
