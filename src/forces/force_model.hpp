// A force model: how stage 4 of a step (architecture.md) turns the contact patches into the
// forces and torques on the bodies, and the contact memory it carries from one step to the
// next. The scene chooses one by contact.model and, for SEMM, contact.solver; each is a unit of
// its own in one folder under src/forces/:
//
//   penalty/      springs and dashpots (contact.model "penalty")
//   semm_newton/  SEMM by Newton's method on the primal problem (the default)
//   semm_rows/    SEMM by projected Gauss-Seidel over scalar rows (contact.solver "rows")
//   semm_blocks/  SEMM by patch blocks (contact.solver "blocks")
//   semm_paper/   the paper's SEMM (contact.model "semm-paper")
//
// force_models.cpp is the one place that knows them all: a new model is a new folder, its
// fields in ContactForces (contact_forces.hpp) and a line there. What the rest of a step asks of
// a model (its memory, the overlap correction, MPI, sliding surfaces) it asks here, so that no
// switch on the model's name is needed elsewhere.
#pragma once

#include <string>
#include <vector>

#include "contact/contact_patch.hpp"
#include "forces/contact_memory.hpp"
#include "world/model.hpp"

namespace tem {

struct ContactForces;   // contact_forces.hpp
class SolverSync;       // solver_sync.hpp
struct SolverSettings;  // semm.hpp

// One solve's inputs (compute_contact_forces, contact_forces.hpp, says what each is).
struct ForceStep {
  const Model& model;
  const State& state;
  const std::vector<ContactPatch>& patches;
  Real dt;
  const ExternalLoads* loads;
  SolverSync* sync;
};

class ForceModel {
 public:
  virtual ~ForceModel() = default;

  // The forces of one step: fills out.force, out.torque (already zero, one per body),
  // out.patch_forces (zero, one per patch), out.points and out.solver, and the model's memory.
  virtual void compute(const ForceStep& step, ContactForces& out) const = 0;

  // The contact memory of the last compute(), one record per contact, in the order of pair_key
  // (contact_patch.hpp); and the inverse, which replaces the model's memory in `forces` with
  // `records` (in that order too). Records that are not the model's own (a damaged checkpoint)
  // throw std::runtime_error.
  virtual void save_memory(const ContactForces& forces, std::vector<MemoryRecord>& out) const = 0;
  virtual void load_memory(const std::vector<MemoryRecord>& records,
                           ContactForces& forces) const = 0;

  // Whether stage 6, the overlap correction (overlap_correction.hpp), follows the model's
  // steps: for a model whose impulses keep the energy budget the correction spends.
  virtual bool corrects_overlap() const { return false; }
  // Its move, by the model's own solver (a model that corrects overlap overrides it): the
  // pseudo velocities f.correction.moved that separate f.points at `targets`, from the bodies
  // f.correction.still, on the working patches f.correction.patches (solve_separation, semm.hpp);
  // `stopping` gives the tolerance, the sweeps, the held points and the ranks.
  virtual void separate(const std::vector<Real>& targets, const SolverSettings& stopping,
                        ContactForces& f) const;
  // Over MPI ranks (docs/distributed.md): whether each contact is solved once, by the ranks
  // together (solver_sync.hpp), its memory with the rank of body A; or each rank finds the
  // forces of its own bodies' contacts, and its memory travels with the bodies it lends to
  // other ranks as well (the penalty model's explicit forces).
  virtual bool solves_across_ranks() const = 0;
  // Why the model does not run over MPI ranks; empty where it does.
  virtual std::string not_distributed_because() const { return {}; }
  // What the model warns of when a scene loads (a time step it cannot keep stable).
  virtual void add_warnings(const Model& /*model*/, std::vector<std::string>& /*warnings*/) const {}
};

// The scene's force model.
const ForceModel& force_model(const ContactDef& contact);

}  // namespace tem
