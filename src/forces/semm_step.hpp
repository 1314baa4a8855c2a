// What the SEMM force models (semm_rows/, semm_blocks/, semm_newton/, semm_paper/) share
// around their solve: the step's contact points and body responses, the default mode's
// start-of-step velocities, coefficients and warm start, and the impulses made forces.
#pragma once

#include "forces/contact_forces.hpp"
#include "forces/force_model.hpp"

namespace tem {

// The last step's points, impulses and friction kept as the warm start; this step's points
// (out.points) and the bodies' responses (out.responses). False when there is nothing to
// solve (no patch, one process).
bool begin_semm_step(const ForceStep& step, ContactForces& out);

// Default mode: each point's and patch's start-of-step velocities and coefficients
// (out.approach, out.friction), the warm start of out.impulses and out.friction from the last
// step's, and the solver's settings from the scene.
SolverSettings begin_default_semm(const ForceStep& step, ContactForces& out);

// The impulses as forces held through the step: on B +j, on A -j, with their moments; with
// `friction`, the patches' friction, twist and rolling impulses too.
void semm_impulses_to_forces(Real dt, bool friction, ContactForces& out);

// The SEMM memory (the warm start: each patch's friction with its points and their normal
// impulses) as records, one per patch with points; and back.
void save_semm_memory(const ContactForces& forces, std::vector<MemoryRecord>& out);
void load_semm_memory(const std::vector<MemoryRecord>& records, ContactForces& forces);

// What the default-mode SEMM models (rows, blocks, newton) have in common besides their solve:
// the warm start as memory, the overlap correction after them, the ranks solving together.
class DefaultSemmModel : public ForceModel {
 public:
  void save_memory(const ContactForces& forces, std::vector<MemoryRecord>& out) const override {
    save_semm_memory(forces, out);
  }
  void load_memory(const std::vector<MemoryRecord>& records,
                   ContactForces& forces) const override {
    load_semm_memory(records, forces);
  }
  bool corrects_overlap() const override { return true; }
  // By the scalar-row solver in its memory f.rows (the blocks model overrides it). Newton's
  // steps too: a correction solved by Newton converges where the sweeps stop at 500, but took
  // ten times as long on a settled pile and cycled in a pour (docs/benchmarks.md, "The BLAS,
  // and the overlap correction by Newton").
  void separate(const std::vector<Real>& targets, const SolverSettings& stopping,
                ContactForces& f) const override;
  bool solves_across_ranks() const override { return true; }
};

}  // namespace tem
