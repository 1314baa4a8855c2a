// A run of one scene shared among MPI ranks (docs/distributed.md), for a program started by
// mpirun: every rank loads the same Simulation (rank 0 records its files), then
// run_distributed() steps it to its duration, each rank the bodies of its part of space. Only
// in a build with TEM_MPI; MPI itself stays behind this header.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "tem/simulation.hpp"

namespace tem {

// True when this process was started by mpirun/mpiexec (Open MPI, MPICH or a PMI launcher),
// however many ranks.
bool launched_by_mpi();

// MPI for the life of the object: started on construction, finished on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const;
  int size() const;
  // The worst (largest) of every rank's `code`: each rank calls it, and all get the same.
  int agreed(int code) const;
  // Ends every rank with `code`: for a failure on one rank while the others wait on it.
  [[noreturn]] void abort(int code) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Why the scene cannot be shared among ranks (a contact model the distributed run does not
// carry), or "" when it can.
std::string distributed_unsupported_reason(const Simulation& sim);

struct DistributedRun {
  enum class End { finished, stopped, not_finite };
  End end = End::finished;
  std::string bad_body;  // End::not_finite: the first body whose state stopped being finite
  long long steps = 0;   // taken by this run
  double wall = 0;       // seconds
  // Rank 0 only: the whole final state's energies and hash, and the contact solver's figures
  // (every rank iterates as often).
  SystemEnergies energies;
  std::string hash_hex;
  RunStatistics solver;
  // Rank 0 only, over the ranks: the fewest and most bodies a rank owned at the end, seconds
  // in exchanges and bytes sent per rank; migrations, ghosts and messages summed over the
  // ranks; rebalancings; averagings of shared bodies and the bytes sent in them, summed.
  int ranks = 1;
  double fewest_bodies = 0, most_bodies = 0;
  double least_exchange_seconds = 0, most_exchange_seconds = 0;
  double least_bytes_sent = 0, most_bytes_sent = 0;
  long long migrations = 0, ghosts = 0, messages = 0, balancings = 0;
  long long shared_averagings = 0, shared_bytes_sent = 0;
};

// Steps `sim` to its total_steps() on the ranks of `mpi`, each rank's own copy of the same
// scene at the same step; rank 0's `sim` records (record() or resume_recording() before), the
// others do not. Checkpoints go to directory/checkpoint.bin, ParaView pieces into directory.
// `stop_requested` is asked on every rank each step: the run stops, after a checkpoint, at the
// first step where any rank says yes. `progress` is called on rank 0 after each step. The
// files are closed when it returns. A file rank 0 cannot write throws std::runtime_error on
// rank 0 while the others wait: end them with mpi.abort().
DistributedRun run_distributed(const MpiSession& mpi, Simulation& sim, const std::string& directory,
                               const std::function<bool()>& stop_requested,
                               const std::function<void(long long, Real)>& progress);

}  // namespace tem
