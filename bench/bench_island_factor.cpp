// The linear solve of SEMM by Newton (src/forces/semm_newton/island_factor.hpp) on the Hessian
// of a resting pile of N coins, one island: H = M + sum J^T G J, with every contact point's
// normal row pushing and every patch's slip and twist rows sticking, G = 1 / R, R = 1e-6 of the
// row's Delassus diagonal (newton_rows.hpp), the matrix every Newton iteration of a settled pile
// factorises. Which linear solver pays at which size:
//   - Eigen's SimplicialLDLT (what island_factor.cpp uses) and SimplicialLLT, AMD ordering;
//   - CHOLMOD's supernodal Cholesky (SuiteSparse, through Eigen's CholmodSupport), what
//     island_factor.cpp uses where the factorisation takes kSupernodalFlopsPerEntry flops an entry;
//   - conjugate gradients preconditioned by the bodies' 6 x 6 blocks (block_jacobi.hpp), or by
//     an incomplete Cholesky factor, to a relative residual of 1e-8.
// Counters: analyse_ms (the symbolic analysis, once per step while the contact graph holds),
// factor_ms (each Newton iteration), solve_ms, factor_nnz (entries of L), cg_iterations.
#include <benchmark/benchmark.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <mutex>
#include <vector>

#include "bench_scenes.hpp"
#include "contact/detect_contacts.hpp"
#include "forces/semm_newton/blas_setup.hpp"
#include "block_jacobi.hpp"
#include "support/parallel.hpp"
#include <Eigen/CholmodSupport>

namespace tem::bench {
namespace {

using SparseMatrix = Eigen::SparseMatrix<Real>;
using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

constexpr Real kRegularisation = 1e-6;  // as newton_rows.hpp

// The resting pile's Newton Hessian, lower and upper triangles, with y = (v, omega) per coin.
struct PileHessian {
  SparseMatrix matrix;
  Eigen::VectorXd rhs;
  int bodies = 0;
  long long rows = 0;
};

PileHessian pile_hessian(int coins) {
  const Model model = coin_pile(coins);
  const State state = initial_state(model);
  ContactWorkspace scratch;
  std::vector<ContactPatch> patches;
  detect_contacts(model, state, patch_variant(model.scene), scratch, patches);

  const int n = static_cast<int>(model.bodies.size());
  std::vector<Mat6> mass(n), inverse(n);
  for (int b = 0; b < n; ++b) {
    const Mat3& g = state.bodies[b].g;
    const Mat3 inertia = g * model.bodies[b].inertia.inertia * g.transpose();
    mass[b].setZero();
    mass[b].topLeftCorner<3, 3>() = model.bodies[b].inertia.mass * Mat3::Identity();
    mass[b].bottomRightCorner<3, 3>() = inertia;
    inverse[b] = mass[b].inverse();
  }
  std::vector<Eigen::Triplet<Real>> entries;
  PileHessian h;
  h.bodies = n;
  for (int b = 0; b < n; ++b)
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) entries.emplace_back(6 * b + r, 6 * b + c, mass[b](r, c));
  // One row: u = Ja y_a + Jb y_b; adds J^T (1 / R) J with R = 1e-6 J W J^T.
  auto add_row = [&](int a, int b, const Vec6& ja, const Vec6& jb) {
    Real w = ja.dot(inverse[a] * ja);
    if (b >= 0) w += jb.dot(inverse[b] * jb);
    const Real g = 1 / (kRegularisation * w);
    const int side[2] = {a, b};
    const Vec6* j[2] = {&ja, &jb};
    for (int s = 0; s < 2; ++s)
      for (int t = 0; t < 2; ++t) {
        if (side[s] < 0 || side[t] < 0) continue;
        const Mat6 block = g * (*j[s]) * j[t]->transpose();
        for (int r = 0; r < 6; ++r)
          for (int c = 0; c < 6; ++c)
            entries.emplace_back(6 * side[s] + r, 6 * side[t] + c, block(r, c));
      }
    ++h.rows;
  };
  auto jacobian = [&](int body, const Vec3& p, const Vec3& d, Real sign) {
    Vec6 j;
    j.head<3>() = sign * d;
    j.tail<3>() = sign * (p - state.bodies[body].x).cross(d);
    return j;
  };
  for (const ContactPatch& patch : patches) {
    const int a = patch.body_a, b = patch.body_b;
    const Vec3& nrm = patch.normal;
    const Vec3 t1 = nrm.unitOrthogonal(), t2 = nrm.cross(t1);
    for (const Vec3& p : patch.vertices)
      add_row(a, b, jacobian(a, p, nrm, -1), b >= 0 ? jacobian(b, p, nrm, 1) : Vec6::Zero());
    for (const Vec3& t : {t1, t2})
      add_row(a, b, jacobian(a, patch.point, t, -1),
              b >= 0 ? jacobian(b, patch.point, t, 1) : Vec6::Zero());
    Vec6 twist_a = Vec6::Zero(), twist_b = Vec6::Zero();
    twist_a.tail<3>() = -nrm;
    twist_b.tail<3>() = nrm;
    add_row(a, b, twist_a, twist_b);
  }
  h.matrix.resize(6 * n, 6 * n);
  h.matrix.setFromTriplets(entries.begin(), entries.end());
  // A right-hand side of the size gravity gives: every coin's weight over a step of 5e-4 s.
  h.rhs = Eigen::VectorXd::Zero(6 * n);
  for (int b = 0; b < n; ++b) h.rhs(6 * b + 2) = -model.bodies[b].inertia.mass * 981 * 5e-4;
  return h;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A direct factorisation: the analysis once, then factorise and solve, timed per iteration.
template <class Factor>
void direct(benchmark::State& st, const PileHessian& h, Factor& factor) {
  auto clock = std::chrono::steady_clock::now();
  factor.analyzePattern(h.matrix);
  const double analyse = ms_since(clock);
  double factor_ms = 0, solve_ms = 0;
  Eigen::VectorXd x;
  for (auto _ : st) {
    clock = std::chrono::steady_clock::now();
    serially([&] { factor.factorize(h.matrix); });  // as island_factor.cpp
    factor_ms += ms_since(clock);
    clock = std::chrono::steady_clock::now();
    x = factor.solve(h.rhs);
    solve_ms += ms_since(clock);
    benchmark::DoNotOptimize(x.data());
  }
  const double runs = static_cast<double>(st.iterations());
  st.counters["analyse_ms"] = analyse;
  st.counters["factor_ms"] = factor_ms / runs;
  st.counters["solve_ms"] = solve_ms / runs;
  st.counters["residual"] = (h.matrix * x - h.rhs).norm() / h.rhs.norm();
  st.counters["bodies"] = h.bodies;
  st.counters["rows"] = static_cast<double>(h.rows);
  st.counters["matrix_nnz"] = static_cast<double>(h.matrix.nonZeros());
}

void BM_IslandFactorEigenLDLT(benchmark::State& st) {
  const PileHessian h = pile_hessian(static_cast<int>(st.range(0)));
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> factor;
  direct(st, h, factor);
  st.counters["factor_nnz"] = static_cast<double>(factor.matrixL().nestedExpression().nonZeros());
}

void BM_IslandFactorEigenLLT(benchmark::State& st) {
  const PileHessian h = pile_hessian(static_cast<int>(st.range(0)));
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> factor;
  direct(st, h, factor);
  st.counters["factor_nnz"] = static_cast<double>(factor.matrixL().nestedExpression().nonZeros());
}

void BM_IslandFactorCholmod(benchmark::State& st) {
  // As island_factor.cpp: the BLAS on one thread, with the kernels of the CPU's instruction sets
  // (OPENBLAS_CORETYPE=Prescott in the environment measures OpenBLAS's fallback instead).
  static std::once_flag blas_prepared;
  std::call_once(blas_prepared, newton::prepare_blas);
  const PileHessian h = pile_hessian(static_cast<int>(st.range(0)));
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> factor;  // as island_factor.cpp
  direct(st, h, factor);
  st.counters["factor_nnz"] = static_cast<double>(factor.cholmod().lnz);
}

template <class Preconditioner>
void conjugate_gradients(benchmark::State& st) {
  const PileHessian h = pile_hessian(static_cast<int>(st.range(0)));
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Preconditioner> cg;
  cg.setTolerance(1e-8);
  cg.setMaxIterations(static_cast<Eigen::Index>(20 * h.matrix.rows()));
  double setup = 0, solve_ms = 0;
  Eigen::VectorXd x;
  for (auto _ : st) {
    auto clock = std::chrono::steady_clock::now();
    cg.compute(h.matrix);
    setup += ms_since(clock);
    clock = std::chrono::steady_clock::now();
    x = cg.solve(h.rhs);
    solve_ms += ms_since(clock);
    benchmark::DoNotOptimize(x.data());
  }
  const double runs = static_cast<double>(st.iterations());
  st.counters["factor_ms"] = setup / runs;  // the preconditioner's set-up
  st.counters["solve_ms"] = solve_ms / runs;
  st.counters["cg_iterations"] = static_cast<double>(cg.iterations());
  st.counters["residual"] = (h.matrix * x - h.rhs).norm() / h.rhs.norm();
  st.counters["bodies"] = h.bodies;
}

void BM_IslandSolveCGBlockJacobi(benchmark::State& st) {
  conjugate_gradients<BlockJacobi>(st);
}
void BM_IslandSolveCGIncompleteCholesky(benchmark::State& st) {
  conjugate_gradients<Eigen::IncompleteCholesky<Real>>(st);
}

#define TEM_ISLAND_SIZES ->Arg(30)->Arg(60)->Arg(100)->Arg(300)->Arg(1000)->Arg(4000)->Arg(10000)->Unit(benchmark::kMillisecond)
BENCHMARK(BM_IslandFactorEigenLDLT) TEM_ISLAND_SIZES;
BENCHMARK(BM_IslandFactorEigenLLT) TEM_ISLAND_SIZES;
BENCHMARK(BM_IslandFactorCholmod) TEM_ISLAND_SIZES;
BENCHMARK(BM_IslandSolveCGBlockJacobi) TEM_ISLAND_SIZES;
BENCHMARK(BM_IslandSolveCGIncompleteCholesky) TEM_ISLAND_SIZES;

}  // namespace
}  // namespace tem::bench
