// Domain decomposition of one run over MPI ranks (LAMMPS's exchange/borders, Solfec's box
// assignment, read for ideas): every rank holds the whole Model and a State as long as the
// scene, but moves only the bodies it OWNS (those whose centre lies in its RCB box) and tests
// contact only among RESIDENT bodies: its own and GHOSTS, copies of bodies owned elsewhere
// that come within contact reach of its own. Workspace::subset says which is which.
//
// Each step, before contact is sought:
//   1. migrate   bodies whose centre left this rank's box go, with their contact memory, to
//                the rank whose box holds it now (Zoltan's kept cuts say which);
//   2. borders   each rank sends every rank whose bodies' reach box meets one of its bodies'
//                reach boxes that body's state and contact memory: after it, every pair of
//                bodies that may touch is resident where either body is owned.
// A contact belongs to the rank that owns its body A (the lower index): its memory is kept
// and its row is written there. Penalty: a contact across a boundary is also evaluated by the
// rank of body B, from the same states and memory, so each rank sums the forces on its own
// bodies from every contact that touches them, in the order one process would (LAMMPS's
// "newton off"): no force travels back, and penalty runs are bit-identical at any rank count.
// SEMM: a contact is on its owner's rank only, all ranks solve together (shared_solve.hpp),
// and the forces on ghosts travel back to their owners (return_ghost_forces).
#pragma once

#include <mpi.h>

#include <memory>
#include <vector>

#include "distributed/contact_memory.hpp"
#include "distributed/rcb_partition.hpp"
#include "distributed/shared_solve.hpp"
#include "forces/contact_forces.hpp"
#include "simulation/step.hpp"

namespace tem::distributed {

// Message sizes and counts since the start, for the run's summary and the scaling model.
struct ExchangeStats {
  long long migrated = 0;       // bodies that changed owner
  long long ghosts = 0;         // ghost copies received, summed over the steps
  long long bytes_sent = 0;     // by this rank, migration and borders
  long long messages_sent = 0;  // non-empty messages to other ranks
  long long balancings = 0;
  double seconds = 0;  // in migrate + borders
};

class Domain {
 public:
  explicit Domain(MPI_Comm comm);

  // The first ownership: every rank holds the same full `state` (a new run or a checkpoint
  // read by every rank). Balances by each body's block count, then keeps, of `forces`' memory,
  // what this rank owns.
  void start(const Model& model, const State& state, Workspace& workspace);

  // Steps 1 and 2 above, at the start of a step.
  void exchange(const Model& model, State& state, Workspace& workspace);

  // SEMM: after the forces, the forces and torques this rank's contacts put on ghosts go to
  // their owners, who add them in rank order (penalty needs none: see above).
  void return_ghost_forces(Workspace& workspace);

  // New cuts when the owned cost is out of balance by more than `tolerance` (max / mean);
  // checked every `every` steps. Costs: a body's blocks plus twice its contacts.
  void balance_if_needed(const Model& model, State& state, Workspace& workspace);

  // The whole State on rank 0 (others: unchanged), in body order.
  void gather_state(const Model& model, const State& state, State& whole) const;
  // The contacts this rank owns, with their forces, gathered on rank 0 in one process's order.
  void gather_contacts(const Workspace& workspace, std::vector<ContactPatch>& patches,
                       std::vector<PatchForce>& forces) const;
  // The contact memory this rank owns (the last step's), gathered on rank 0 in one process's
  // order: what a one-process checkpoint holds.
  void gather_memory(const Model& model, const ContactForces& forces, ContactForces& whole) const;

  // The first body, in scene order, whose owned state is not finite on any rank, or -1.
  int first_non_finite_body(const State& state) const;

  int rank() const { return rank_; }
  int size() const { return size_; }
  long long owned_count() const;
  const ExchangeStats& stats() const { return stats_; }
  const SharedSolve* shared_solve() const { return shared_.get(); }

  int balance_every = 50;
  double balance_tolerance = 1.2;

 private:
  void keep_owned_memory(const Model& model, Workspace& workspace) const;
  void migrate(const Model& model, State& state, Workspace& workspace);
  void borders(const Model& model, State& state, Workspace& workspace);
  // Sends send[r] to rank r; takes in the bodies the others sent (their state, and their
  // memory appended to arrived_) and returns each with the rank that sent it.
  std::vector<std::pair<int, int>> deliver(const std::vector<std::vector<double>>& send,
                                           State& state);

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  RcbPartition partition_;
  std::vector<int> owned_ids_;  // this rank's bodies, ascending
  std::vector<int> ghost_ids_;  // the ghosts of this step
  std::vector<int> owner_;      // the rank of every resident body
  bool solved_once_ = false;    // SEMM: each contact on one rank, solved by all together
  std::unique_ptr<SharedSolve> shared_;
  std::vector<MemoryRecord> arrived_;  // memory that came with bodies from other ranks
  long long steps_since_balance_ = 0;
  ExchangeStats stats_;
  // Scratch.
  std::vector<Real> reach_;
};

}  // namespace tem::distributed
