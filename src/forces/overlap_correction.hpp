// Correction of existing overlap that adds no energy (default mode; method.md §6).
//
// The velocity-level contact of SEMM stops bodies approaching but leaves the overlap that one
// step of approach made (impact speed x dt). This pushes overlapping points apart by moving the
// bodies (positions and attitudes, not velocities: no bounce) by the overlap beyond a slop of
// 5e-4 of the body's size (kOverlapSlop), solved like the contact impulses but on pseudo
// velocities (a "split impulse"), in one step: a body that has just landed dissipates then, and
// not afterwards. Lifting a body raises its potential energy, so the move is scaled down to what
// the step's contacts dissipated: the total energy never rises. A body resting still (nothing
// dissipated) keeps its overlap; an impact, which dissipates far more than the lift costs, is
// corrected in the step it happens.
//
// Points already in contact and not deeper than the slop are held (their impulse may take either
// sign): the move carries what rests on a lifted body along instead of opening a gap that it
// would fall back into, whose landing would fund the next lift (method.md, "Correction of
// existing overlap").
#pragma once

#include "forces/contact_forces.hpp"
#include "world/model.hpp"

namespace tem {

// The overlap left alone, as a fraction of the smaller body's size (model.hpp body_size).
// Why not less: a settled pile sinks by round-off and unconverged sweeps into what the contacts
// hold, a little every step. At 1e-4 the correction ran in every step of the settled coins_1000
// pile, each run moving coins apart into gaps they fell back into the next step: the sweeps
// never converged (18.6 of 20 per step on average), coins crept at 0.05 cm/s and the
// correction's own solve cost a fifth of the step. At 5e-4 (a tenth of Box2D's linear slop
// for a body of its scale) it stops once the pile has settled: 1.8 sweeps per step, the pile at
// rest, the 1,000-coin pour right at dt 1.25e-4 (docs/benchmarks.md).
inline constexpr Real kOverlapSlop = 5e-4;

struct CorrectionReport {
  bool applied = false;
  Real scale = 0;  // the fraction of the wanted move that the energy allowed
};

// After integration: `energy_before` is the system's energy at the start of the step, `forces`
// the step's contact forces (points, responses, centres, patches).
// With `sync` (MPI ranks, solver_sync.hpp) every rank calls it: the energies and the move's
// cost are the ranks' sums, the solve is shared, and each rank moves the bodies it owns.
// `dt`: the step (or sub-step) the forces were found for.
CorrectionReport correct_overlap(const Model& model, ContactForces& forces, Real dt,
                                 Real energy_before, State& state, SolverSync* sync = nullptr);

}  // namespace tem
