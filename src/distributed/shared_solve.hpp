// The SEMM solve shared among ranks (solver_sync.hpp says the method: mass splitting, copies'
// velocities averaged after every sweep). The owner of a body that other ranks' contacts touch
// is where its copies meet: each touching rank sends it its copy's velocities, it takes the
// mean (in rank order, so the same bits at every run) and sends the mean back. The owner takes
// part even when none of its own contacts touches the body: it moves the body, so it needs the
// velocities the solve gave it (the overlap correction's move).
#pragma once

#include <mpi.h>

#include <vector>

#include "dynamics/body_state.hpp"
#include "forces/contact_points.hpp"
#include "forces/solver_sync.hpp"

namespace tem::distributed {

class SharedSolve : public SolverSync {
 public:
  // `owner`: the rank of every resident body (valid for the subset's resident ones).
  SharedSolve(MPI_Comm comm, const BodySubset& subset, const std::vector<int>& owner);

  const std::vector<BodyResponse>& split(const std::vector<ContactPoint>& points,
                                         const std::vector<BodyResponse>& bodies) override;
  const std::vector<BodyResponse>& unsplit() const override { return *given_; }
  void average(std::vector<SlotVelocity>& slots) override;
  SweepSize largest(const SweepSize& mine) override;
  Real sum(Real mine) override;
  bool owns(int body) const override { return subset_.owned[body] != 0; }

  // Messages and reductions since the start, for the run's summary.
  long long averages = 0, bytes_sent = 0;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  const BodySubset& subset_;
  const std::vector<int>& owner_;
  const std::vector<BodyResponse>* given_ = nullptr;
  std::vector<BodyResponse> split_;
  // Of the last split: the ghosts this rank's rows touch (it sends their copies to their
  // owners), and for each owned body other ranks touch, those ranks, ascending, and whether
  // this rank's rows touch it too.
  std::vector<int> touched_ghosts_;
  struct Meeting {
    int body;
    bool here;               // this rank's rows touch it
    std::vector<int> ranks;  // the other ranks whose rows touch it
  };
  std::vector<Meeting> meetings_;
};

}  // namespace tem::distributed
