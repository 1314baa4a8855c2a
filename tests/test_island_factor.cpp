// The linear solve of SEMM by Newton (src/forces/semm_newton/island_factor.hpp) on Hessians of
// the shape a pile and a chain give: H = M + sum over touching pairs of a coupling C (positive
// semidefinite, -C between the two bodies), symmetric positive definite. A lattice of bodies
// (a pile's pattern: its factor fills in) takes CHOLMOD's supernodal factorisation, a chain
// (a column's: no fill) Eigen's; both solve H x = b to round-off, agree with a dense Cholesky,
// and give the same bits at one and two OpenMP threads (the BLAS held to one). Pairs whose block
// is 0 (contacts that do not push) are left out of the factor's pattern. A lattice of
// kIterativeBodies bodies or more is solved by conjugate gradients to the accuracy asked; a
// chain as long keeps its factorisation.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "forces/semm_newton/blas_setup.hpp"
#include "forces/semm_newton/island_factor.hpp"
#include "support/parallel.hpp"

namespace tem {
namespace test_island_factor {

using newton::IslandFactor;
using newton::Mat6;

struct Hessian {
  int bodies = 0;
  std::vector<std::pair<int, int>> pairs;  // (i > j), sorted
  std::vector<Mat6> diagonal, off_diagonal;
  Eigen::MatrixXd dense;  // the same matrix, whole
};

// Bodies at the points of an nx x ny x nz lattice, each coupled to its six neighbours. With
// `pushing` < 1, each pair is coupled with that probability, and otherwise is a pair whose rows
// are all apart (a contact within the margin that does not push): in the pattern, its block 0.
// `whole`: with the dense copy (too large beyond a few hundred bodies).
Hessian lattice(int nx, int ny, int nz, unsigned seed, Real pushing = 1, bool whole = true) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> uniform(-1, 1);
  auto random_block = [&] {
    Mat6 a;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) a(r, c) = uniform(random);
    return a;
  };
  Hessian h;
  h.bodies = nx * ny * nz;
  auto index = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int b = index(i, j, k);
        if (i > 0) h.pairs.emplace_back(b, index(i - 1, j, k));
        if (j > 0) h.pairs.emplace_back(b, index(i, j - 1, k));
        if (k > 0) h.pairs.emplace_back(b, index(i, j, k - 1));
      }
  std::sort(h.pairs.begin(), h.pairs.end());
  h.diagonal.assign(h.bodies, Mat6::Identity());  // the mass matrix, here of unit masses
  if (whole) h.dense = Eigen::MatrixXd::Identity(6 * h.bodies, 6 * h.bodies);
  for (const auto& [i, j] : h.pairs) {
    if (pushing < 1 && (uniform(random) + 1) / 2 >= pushing) {
      h.off_diagonal.push_back(Mat6::Zero());
      continue;
    }
    const Mat6 a = random_block();
    const Mat6 c = 1e3 * a * a.transpose();  // stiff as a regularised contact, beside the mass
    h.diagonal[i] += c;
    h.diagonal[j] += c;
    h.off_diagonal.push_back(-c);
    if (!whole) continue;
    h.dense.block<6, 6>(6 * i, 6 * i) += c;
    h.dense.block<6, 6>(6 * j, 6 * j) += c;
    h.dense.block<6, 6>(6 * i, 6 * j) -= c;
    h.dense.block<6, 6>(6 * j, 6 * i) -= c;
  }
  return h;
}

Eigen::VectorXd solve_at(const Hessian& h, const Eigen::VectorXd& b, int threads, bool& supernodal,
                         bool* iterative = nullptr) {
  const int before = max_threads();
  set_threads(threads);
  IslandFactor factor;
  factor.set_pattern(h.bodies, h.pairs);
  Eigen::VectorXd x;
  EXPECT_TRUE(factor.factorise(h.diagonal, h.off_diagonal));
  factor.solve(b, x);
  supernodal = factor.supernodal();
  if (iterative) *iterative = factor.iterative();
  set_threads(before);
  return x;
}

void expect_solved(const Hessian& h, bool supernodal_expected) {
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * h.bodies, -1, 2);
  bool supernodal_one = false, supernodal_two = false;
  const Eigen::VectorXd one = solve_at(h, b, 1, supernodal_one);
  const Eigen::VectorXd two = solve_at(h, b, 2, supernodal_two);
  EXPECT_EQ(supernodal_one, supernodal_expected);
  EXPECT_EQ(supernodal_two, supernodal_expected);
  // Normwise backward error (Higham, Accuracy and Stability of Numerical Algorithms, 7.1): a
  // stable factorisation's answer solves a matrix within round-off of H. Measured 5e-18 to
  // 1.2e-17 (Frobenius norms), under eps.
  const Real backward = (h.dense * one - b).norm() / (h.dense.norm() * one.norm() + b.norm());
  EXPECT_LT(backward, 1e-16);
  const Eigen::VectorXd dense = h.dense.llt().solve(b);
  EXPECT_LT((one - dense).norm() / dense.norm(), 1e-9);
  for (Eigen::Index i = 0; i < one.size(); ++i) ASSERT_EQ(one(i), two(i)) << i;
}

// Once a supernodal factorisation has set the BLAS up, OpenBLAS runs kernels of the instruction
// sets the CPU has, not its SSE3 fallback for a CPU it does not know (blas_setup.cpp).
TEST(IslandFactor, BlasRunsKernelsOfTheCpusInstructionSets) {
  expect_solved(lattice(7, 7, 7, 1), true);
  const std::string kernels = newton::blas_kernels();
  if (kernels.empty()) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  if (std::getenv("OPENBLAS_CORETYPE")) GTEST_SKIP() << "OPENBLAS_CORETYPE chooses the kernels";
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
    GTEST_SKIP() << "the CPU has no AVX2 and FMA";
  ::testing::Test::RecordProperty("OpenBLAS kernels", kernels);
  EXPECT_NE(kernels, "Prescott");
}

// A 7 x 7 x 7 lattice: its factor holds about 100 entries a column, above the switch (40).
TEST(IslandFactor, LatticeTakesTheSupernodalFactorisation) {
  expect_solved(lattice(7, 7, 7, 1), true);
  expect_solved(lattice(6, 8, 5, 2), true);
}

// A chain of 60 bodies: its factor has the matrix's own entries only.
TEST(IslandFactor, ChainTakesTheSimplicialFactorisation) {
  expect_solved(lattice(60, 1, 1, 3), false);
  expect_solved(lattice(20, 2, 1, 4), false);
}

// A factor kept from step to step: the same pattern again keeps its analysis (and writes the
// new values where the last ones were), a new one is analysed afresh; either way the answer has
// the same bits as a factor made for that matrix alone (a resumed run makes that one).
TEST(IslandFactor, KeptAnalysisGivesTheBitsOfAFreshOne) {
  // The third has the first's number of bodies but another pattern.
  const Hessian steps[] = {lattice(7, 7, 7, 5),  lattice(7, 7, 7, 6),  lattice(49, 7, 1, 7),
                           lattice(6, 8, 5, 8),  lattice(60, 1, 1, 9), lattice(60, 1, 1, 10)};
  const int analyses[] = {1, 1, 2, 3, 4, 4};
  IslandFactor kept;
  for (int k = 0; k < 6; ++k) {
    const Hessian& h = steps[k];
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * h.bodies, -1, 2);
    kept.set_pattern(h.bodies, h.pairs);
    Eigen::VectorXd x;
    ASSERT_TRUE(kept.factorise(h.diagonal, h.off_diagonal));
    kept.solve(b, x);
    EXPECT_EQ(kept.analyses(), analyses[k]) << k;
    bool supernodal = false;
    const Eigen::VectorXd fresh = solve_at(h, b, 1, supernodal);
    EXPECT_EQ(kept.supernodal(), supernodal) << k;
    for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x(i), fresh(i)) << k << " " << i;
  }
}

// A pair whose block is 0 (its rows all apart) is left out of the factor's pattern: a lattice in
// which a sixth of the pairs push falls apart into clusters whose factor barely fills in, and so
// takes Eigen's simplicial factorisation where the whole lattice takes CHOLMOD's supernodal one;
// it solves H x = b as the dense Cholesky does. Within a step (no set_pattern between) a pair
// that starts to push joins the pattern, which is analysed afresh and gives the bits of a factor
// made for that matrix alone; it stays while the step lasts; the next step starts again from the
// pairs that push in it.
TEST(IslandFactor, PairsThatDoNotPushAreLeftOutOfThePattern) {
  const Hessian loose = lattice(7, 7, 7, 11, 1.0 / 6);
  expect_solved(loose, false);
  const Hessian tight = lattice(7, 7, 7, 12);  // the same contact graph, every pair pushing
  ASSERT_EQ(loose.pairs, tight.pairs);
  IslandFactor kept;
  auto factorise = [&](const Hessian& h, int analyses, bool supernodal) {
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * h.bodies, -1, 2);
    Eigen::VectorXd x;
    ASSERT_TRUE(kept.factorise(h.diagonal, h.off_diagonal));
    kept.solve(b, x);
    EXPECT_EQ(kept.analyses(), analyses);
    EXPECT_EQ(kept.supernodal(), supernodal);
    const Eigen::VectorXd dense = h.dense.llt().solve(b);
    EXPECT_LT((x - dense).norm() / dense.norm(), 1e-9);
    bool fresh_supernodal = false;
    const Eigen::VectorXd fresh = solve_at(h, b, 1, fresh_supernodal);
    if (fresh_supernodal == supernodal) {
      for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x(i), fresh(i)) << i;
    }
  };
  kept.set_pattern(loose.bodies, loose.pairs);
  factorise(loose, 1, false);
  factorise(tight, 2, true);   // every pair joins: analysed afresh
  factorise(loose, 2, true);   // the same step: the pairs stay
  kept.set_pattern(loose.bodies, loose.pairs);  // the next step
  factorise(loose, 3, false);
}

// H x from the blocks, and the size of a vector in the norm of the diagonal blocks' inverse (the
// norm conjugate gradients' accuracy is asked in).
Eigen::VectorXd times(const Hessian& h, const Eigen::VectorXd& x) {
  Eigen::VectorXd out(x.size());
  for (int b = 0; b < h.bodies; ++b) out.segment<6>(6 * b) = h.diagonal[b] * x.segment<6>(6 * b);
  for (size_t k = 0; k < h.pairs.size(); ++k) {
    const auto [i, j] = h.pairs[k];
    out.segment<6>(6 * i) += h.off_diagonal[k] * x.segment<6>(6 * j);
    out.segment<6>(6 * j) += h.off_diagonal[k].transpose() * x.segment<6>(6 * i);
  }
  return out;
}
Real block_norm(const Hessian& h, const Eigen::VectorXd& r) {
  Real sum = 0;
  for (int b = 0; b < h.bodies; ++b) {
    const newton::Vec6 part = r.segment<6>(6 * b);
    sum += part.dot(h.diagonal[b].llt().solve(part));
  }
  return std::sqrt(sum);
}

// Conjugate gradients asked for round-off accuracy give the dense Cholesky's answer; asked for
// 1e-2, an answer whose residual is at most 1e-2 of the right-hand side in the blocks' norm, and
// a direction of descent (b . x > 0: the Newton step lowers the objective).
TEST(IslandFactor, ConjugateGradientsSolveToTheAccuracyAsked) {
  const Hessian h = lattice(5, 5, 5, 13);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * h.bodies, -1, 2);
  newton::BlockConjugateGradients cg;
  ASSERT_TRUE(cg.prepare(h.bodies, h.pairs, h.diagonal, h.off_diagonal));
  Eigen::VectorXd x;
  const int many = cg.solve(b, x, 1e-13, 6 * h.bodies);
  const Eigen::VectorXd dense = h.dense.llt().solve(b);
  EXPECT_LT((x - dense).norm() / dense.norm(), 1e-9);
  const int few = cg.solve(b, x, 1e-2, 6 * h.bodies);
  ::testing::Test::RecordProperty("iterations to 1e-13", many);
  ::testing::Test::RecordProperty("iterations to 1e-2", few);
  EXPECT_LT(few, many);
  EXPECT_LE(block_norm(h, b - times(h, x)), 1e-2 * block_norm(h, b));
  EXPECT_GT(b.dot(x), 0);
}

// An island of at least kIterativeBodies bodies whose factor would fill in (an 8 x 8 x 8
// lattice, 512 bodies) is solved by conjugate gradients, to kIterativeAccuracy, with the same
// bits at one and two threads and when kept into the next step; a chain as long (600 bodies)
// keeps its simplicial factorisation and solves to round-off.
TEST(IslandFactor, LargeIslandThatFillsInTakesConjugateGradients) {
  const Hessian pile = lattice(8, 8, 8, 14, 1, false);
  ASSERT_GE(pile.bodies, newton::kIterativeBodies);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * pile.bodies, -1, 2);
  std::vector<Eigen::VectorXd> answers;
  for (int threads : {1, 2}) {
    bool supernodal = true, iterative = false;
    answers.push_back(solve_at(pile, b, threads, supernodal, &iterative));
    EXPECT_TRUE(iterative);
    EXPECT_FALSE(supernodal);
    EXPECT_LE(block_norm(pile, b - times(pile, answers.back())),
              newton::kIterativeAccuracy * block_norm(pile, b));
  }
  for (Eigen::Index i = 0; i < answers[0].size(); ++i) ASSERT_EQ(answers[0](i), answers[1](i)) << i;
  // Kept into the next step (the same pattern, other values), the choice and the bits are a
  // fresh factor's (a resumed run's).
  const Hessian next = lattice(8, 8, 8, 16, 1, false);
  ASSERT_EQ(next.pairs, pile.pairs);
  IslandFactor kept;
  Eigen::VectorXd x;
  for (const Hessian* h : {&pile, &next}) {
    kept.set_pattern(h->bodies, h->pairs);
    ASSERT_TRUE(kept.factorise(h->diagonal, h->off_diagonal));
    kept.solve(b, x);
  }
  bool supernodal = true, iterative = false;
  const Eigen::VectorXd fresh = solve_at(next, b, 1, supernodal, &iterative);
  EXPECT_TRUE(kept.iterative());
  for (Eigen::Index i = 0; i < x.size(); ++i) ASSERT_EQ(x(i), fresh(i)) << i;

  const Hessian chain = lattice(600, 1, 1, 15, 1, false);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(6 * chain.bodies, -1, 2);
  const Eigen::VectorXd y = solve_at(chain, c, 1, supernodal, &iterative);
  EXPECT_FALSE(iterative);
  EXPECT_FALSE(supernodal);
  EXPECT_LT((times(chain, y) - c).norm() / c.norm(), 1e-12);
}

}  // namespace test_island_factor
}  // namespace tem
