// Default SEMM, one scalar row per contact point: the same convex programme as solve_semm
// (semm.hpp: the impulses that minimise the energy at the next step, normal impulses >= 0,
// each patch's friction inside mu times its normal impulse), solved by projected Gauss-Seidel
// with every normal impulse a scalar of its own instead of a patch block.
//
// Why: a patch block (up to eight points, Lawson-Hanson at every sweep) made a step cost 20-30
// us per patch. Here a patch has at most four points (block_manifold.hpp) and a sweep visits
// each with a few dot products: every row's Jacobian and its response (arm x n and
// Q (arm x n) for both bodies, the inverse of n.K n) is computed once per step, each body's
// pseudo velocity kept in one flat array with one still slot for walls and fixed bodies. What
// scalar rows give up is the exact answer of a patch's coupled points within one sweep (a tall
// column rocking on its end); warm starting from the last step's impulses carries that
// convergence from step to step, as Box2D, Box3D and Jolt do.
//
// Order: each patch's normal rows, then its friction (2x2 tangential block and twist, with the
// start-of-step energy rule of semm.cpp), patch after patch. The threads share each sweep
// level by level (patch_colouring.hpp, level_patches), with the bits of one thread going patch
// by patch; with colour_sweeps the patches go colour by colour and threads share a colour, the
// same bits at any thread count but another answer. Rows are built and laid out in the sweeps'
// order, contiguous per patch, in memory reused from step to step: nothing is allocated once the
// pile's size has been seen. Sums over all rows (the warm start, the energy check) still run in
// patch order, so that the layout never changes a bit.
#pragma once

#include <vector>

#include "forces/patch_colouring.hpp"
#include "forces/semm.hpp"

namespace tem {

// The solver's memory, kept between steps so that a running pile allocates nothing.
struct RowSolverMemory {
  struct NormalRow {
    int a = 0, b = 0;  // body slots (the still slot for walls and fixed bodies)
    Vec3 normal, arm_a_x_n, arm_b_x_n, turn_a, turn_b;  // turn = Q (arm x n)
    Real inverse_k = 0, target = 0, impulse = 0, lever = 0;  // lever: distance to the centre
    Real floor = 0;  // the least impulse: 0, or -infinity for a held row (SolverSettings::held)
  };
  struct FrictionRow {
    int a = 0, b = 0;
    int first = 0, last = 0;  // its normal rows
    Vec3 tangent1, tangent2, normal;
    Vec3 arm_a_x_t1, arm_a_x_t2, arm_b_x_t1, arm_b_x_t2;
    Vec3 turn_a_t1, turn_a_t2, turn_b_t1, turn_b_t2, turn_a_n, turn_b_n;
    Eigen::Matrix<Real, 2, 2> inverse_k_slip;
    Real inverse_k_twist = 0;  // 0: no twist row (both sides without rotation)
    Vec3 start_slip;
    Vec3 surface_slip;  // what sliding surfaces add to the slip (PatchFriction::surface_slip)
    Real t1 = 0, t2 = 0, twist = 0;
    Real mu = 0;       // the patch's friction coefficient
    int rolling = -1;  // its rolling row in `rolling`, or -1: none
    // The patch's normal rows solved together (semm_rows.cpp, patch_block): the pseudo-inverse
    // of their K, for a patch of three or four points not on one line; `block` false: none.
    Eigen::Matrix<Real, 4, 4> k_pseudo_inverse = Eigen::Matrix<Real, 4, 4>::Zero();
    bool block = false;
  };
  // Rolling resistance of a patch with mu_r > 0: a bounded 2-D angular row, an angular impulse
  // about the patch's tangents (on B, the opposite on A) inside the disc mu_r R (sum of the
  // patch's normal impulses); patches without it have none and cost nothing.
  struct RollingRow {
    int a = 0, b = 0;
    Vec3 tangent1, tangent2;
    Vec3 turn_a1, turn_a2, turn_b1, turn_b2;  // Q t
    Eigen::Matrix<Real, 2, 2> inverse_k;
    Real limit = 0;   // mu_r R
    Real radius = 0;  // R: the impulse's scale for the sweeps' change
    Eigen::Matrix<Real, 2, 1> start = Eigen::Matrix<Real, 2, 1>::Zero();
    Real r1 = 0, r2 = 0;
  };
  std::vector<SlotVelocity> slots;  // pseudo velocities per slot
  std::vector<Real> inverse_mass;
  std::vector<NormalRow> rows;
  std::vector<FrictionRow> friction;
  std::vector<RollingRow> rolling;
  std::vector<int> point_of_row, patch_of_friction;
  // Where the patches' rows lie, in the order of the serial sweep the threads reproduce: patch
  // order for levels, the layout itself for colours and on one thread. Sums over all rows (the
  // energy check) run in it.
  std::vector<int> serial_order;
  struct EnergyTerm {
    Real added = 0, curvature = 0;  // energy_scale's, for one row
  };
  std::vector<EnergyTerm> row_energy, patch_energy;
  std::vector<SweepSize> sizes;
  std::vector<SlotVelocity> free;  // the velocities without impulses: energy check (semm_rows.cpp)
  std::vector<BodyResponse> now;  // the bodies after stopped sweeps (semm_rows.cpp)
  Colouring colouring;            // the sweeps' order, its vectors reused step after step
  // Conjugate gradients (semm_rows.cpp: sweeps): the impulses before the sweep, its step,
  // and the search direction, normal rows first, then each friction row's (t1, t2).
  std::vector<Real> before, direction;
};

// Default SEMM with scalar normal rows. `start` is each point's normal relative velocity at the
// start of the step, `targets` from normal_targets(); `patches` and `impulses` hold the warm
// start on entry and the result on return, as for solve_semm. Should the sweeps stop short with
// impulses that would add energy over the step, all are scaled down until they add none
// (report.scale < 1). An empty `start` skips that check (the overlap correction's solve, whose
// result is a move, not impulses); the slots' velocities are left in `memory` either way.
SolverReport solve_semm_rows(const std::vector<ContactPoint>& points,
                             const std::vector<Real>& start, const std::vector<Real>& targets,
                             const std::vector<BodyResponse>& bodies,
                             const std::vector<Vec3>& centres, const SolverSettings& settings,
                             std::vector<PatchFriction>& patches,
                             std::vector<PointImpulse>& impulses, RowSolverMemory& memory);

}  // namespace tem
