#include "forces/semm_newton/island_factor.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/OrderingMethods>
#include <algorithm>
#include <mutex>

#include "forces/semm_newton/blas_setup.hpp"
#include "support/parallel.hpp"

namespace tem::newton {

// Given the matrix in the order order_bodies() chose, with no ordering of its own: Eigen's
// would order the six times larger graph of the unknowns, and permute the matrix again in every
// factorisation.
struct IslandFactor::SimplicialFactor
    : Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>, Eigen::Upper,
                            Eigen::NaturalOrdering<int>> {
  // The factorisation's flops per entry of L, from the entries below the diagonal of each of
  // L's columns that the symbolic analysis counts (SimplicialCholeskyBase::analyzePattern): a
  // column of c entries costs some c^2 flops. CHOLMOD chooses between its own simplicial and
  // supernodal factorisations by the same ratio (Common->fl / Common->lnz against
  // supernodal_switch, 40).
  double flops_per_entry() const {
    double flops = 0, entries = 0;
    for (Eigen::Index j = 0; j < m_nonZerosPerCol.size(); ++j) {
      const double column = m_nonZerosPerCol[j];
      flops += column * column;
      entries += column;
    }
    return entries > 0 ? flops / entries : 0;
  }
};

// Given a symmetric matrix's upper triangle, CHOLMOD's supernodal factorisation permutes and
// transposes it once a factorisation (cholmod_factorize: "the fastest option for factoring a
// permuted matrix"); given the lower, twice.
struct IslandFactor::SupernodalFactor
    : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<Real>, Eigen::Upper> {};

IslandFactor::IslandFactor() = default;
IslandFactor::IslandFactor(const IslandFactor& other) { *this = other; }
IslandFactor& IslandFactor::operator=(const IslandFactor& other) {
  if (this != &other) set_pattern(other.bodies_, other.pairs_);
  return *this;
}
IslandFactor::IslandFactor(IslandFactor&&) noexcept = default;
IslandFactor& IslandFactor::operator=(IslandFactor&&) noexcept = default;
IslandFactor::~IslandFactor() = default;

void IslandFactor::set_pattern(int bodies, const std::vector<std::pair<int, int>>& pairs) {
  live_.assign(pairs.size(), 0);
  iterative_this_step_ = false;
  // The same contact graph as the last step's (a resting island's): its analysis and choice of
  // factorisation stand while the same pairs push.
  if (bodies == bodies_ && pairs == pairs_) return;
  bodies_ = bodies;
  pairs_ = pairs;
  kind_ = bodies <= kDenseBodies ? Kind::dense : Kind::simplicial;
  analysed_ = false;
}

void IslandFactor::mark_live(const std::vector<Mat6>& off_diagonal) {
  for (size_t k = 0; k < pairs_.size(); ++k)
    if (!live_[k] && !off_diagonal[k].isZero(0)) live_[k] = 1;
  if (live_ != analysed_live_) analysed_ = false;
}

void IslandFactor::order_bodies() {
  Eigen::SparseMatrix<Real> graph(bodies_, bodies_);
  std::vector<Eigen::Triplet<Real>> edges;
  edges.reserve(static_cast<size_t>(bodies_) + pairs_.size());
  for (int b = 0; b < bodies_; ++b) edges.emplace_back(b, b, 1);
  for (size_t k = 0; k < pairs_.size(); ++k)
    if (live_[k]) edges.emplace_back(pairs_[k].second, pairs_[k].first, 1);
  graph.setFromTriplets(edges.begin(), edges.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(graph, order);  // order.indices()[k]: the body in place k
  position_.resize(static_cast<size_t>(bodies_));
  for (int k = 0; k < bodies_; ++k) position_[order.indices()[k]] = k;
}

bool IslandFactor::factorise(const std::vector<Mat6>& diagonal,
                             const std::vector<Mat6>& off_diagonal) {
  const int n = 6 * bodies_;
  if (kind_ == Kind::dense) {
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
  // Upper triangle, with body b's unknowns at 6 position_[b]: the diagonal blocks' upper halves
  // and every live pair's block, at block row min(position) and block column max(position).
  // Explicit zeros are kept, so that the pattern, and with it the symbolic analysis, stays the
  // same. The matrix is built from triplets once per pattern, which also finds where each entry
  // lands in its storage; later factorisations write the values there (the same values in the
  // same places: the same bits).
  mark_live(off_diagonal);
  // Conjugate gradients chosen in this step stay for the step (its pattern only gains pairs, and
  // a factor would only fill in further); chosen in an earlier one, they stand while the pairs
  // that push are those they were chosen for, as a fresh factor's choice would (a resumed run's).
  if (kind_ == Kind::iterative && (iterative_this_step_ || analysed_)) {
    iterative_this_step_ = true;
    return conjugate_gradients_.prepare(bodies_, pairs_, diagonal, off_diagonal);
  }
  const bool built = analysed_;
  if (!built) order_bodies();
  size_t next = 0;
  std::vector<Eigen::Triplet<Real>> triplets;  // a new pattern's entries, until it is built
  auto entry = [&](int r, int c, Real value) {
    if (built) sparse_matrix_.valuePtr()[value_index_[next++]] = value;
    else triplets.emplace_back(r, c, value);
  };
  if (!built) triplets.reserve(static_cast<size_t>(21 * bodies_) + 36 * pairs_.size());
  for (int b = 0; b < bodies_; ++b) {
    const int at = 6 * position_[b];
    for (int c = 0; c < 6; ++c)
      for (int r = c; r < 6; ++r) entry(at + c, at + r, diagonal[b](r, c));
  }
  for (size_t k = 0; k < pairs_.size(); ++k) {
    if (!live_[k]) continue;
    // The block (i, j) is off_diagonal[k]; its transpose is (j, i).
    const int i = 6 * position_[pairs_[k].first], j = 6 * position_[pairs_[k].second];
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r) {
        if (i < j) entry(i + r, j + c, off_diagonal[k](r, c));
        else entry(j + c, i + r, off_diagonal[k](r, c));
      }
  }
  if (!built) {
    sparse_matrix_.resize(n, n);
    sparse_matrix_.setFromTriplets(triplets.begin(), triplets.end());
    value_index_.resize(triplets.size());
    const auto* outer = sparse_matrix_.outerIndexPtr();
    const auto* inner = sparse_matrix_.innerIndexPtr();
    for (size_t t = 0; t < triplets.size(); ++t) {
      const Eigen::Index c = triplets[t].col();
      value_index_[t] = std::lower_bound(inner + outer[c], inner + outer[c + 1],
                                         triplets[t].row()) - inner;
    }
  }
  if (!analysed_) {
    analysed_ = true;
    analysed_live_ = live_;
    ++analyses_;
    kind_ = Kind::simplicial;
    if (!simplicial_factor_) simplicial_factor_ = std::make_unique<SimplicialFactor>();
    simplicial_factor_->analyzePattern(sparse_matrix_);
    if (simplicial_factor_->flops_per_entry() >= kSupernodalFlopsPerEntry &&
        bodies_ >= kIterativeBodies) {
      kind_ = Kind::iterative;
      iterative_this_step_ = true;
      simplicial_factor_.reset();
      supernodal_factor_.reset();  // a factor of an earlier step would only hold its memory
      return conjugate_gradients_.prepare(bodies_, pairs_, diagonal, off_diagonal);
    }
    if (simplicial_factor_->flops_per_entry() >= kSupernodalFlopsPerEntry) {
      kind_ = Kind::supernodal;
      simplicial_factor_.reset();  // its storage for L: some 7 MB on a 1,000-coin pile
      static std::once_flag blas_prepared;
      std::call_once(blas_prepared, prepare_blas);
      if (!supernodal_factor_) supernodal_factor_ = std::make_unique<SupernodalFactor>();
      serially([&] { supernodal_factor_->analyzePattern(sparse_matrix_); });
    }
  }
  if (kind_ == Kind::simplicial) {
    simplicial_factor_->factorize(sparse_matrix_);
    return simplicial_factor_->info() == Eigen::Success;
  }
  serially([&] { supernodal_factor_->factorize(sparse_matrix_); });
  return supernodal_factor_->info() == Eigen::Success;
}

void IslandFactor::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (kind_ == Kind::iterative) {
    conjugate_gradients_.solve(b, x, kIterativeAccuracy, kMostIterations);
    return;
  }
  if (kind_ == Kind::dense) {
    x = dense_factor_.solve(b);
    return;
  }
  ordered_.resize(b.size());
  for (int k = 0; k < bodies_; ++k) ordered_.segment<6>(6 * position_[k]) = b.segment<6>(6 * k);
  if (kind_ == Kind::simplicial) answer_ = simplicial_factor_->solve(ordered_);
  else serially([&] { answer_ = supernodal_factor_->solve(ordered_); });
  x.resize(b.size());
  for (int k = 0; k < bodies_; ++k) x.segment<6>(6 * k) = answer_.segment<6>(6 * position_[k]);
}

}  // namespace tem::newton
