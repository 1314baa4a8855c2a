// MPI for `tem run` under mpirun (MPI stays in src/distributed/ and src/api/distributed_run.cpp,
// behind include/tem/distributed.hpp). TEM starts MPI only when a launcher started it: the same
// binary runs serially, without touching MPI, when started on its own.
#pragma once

#include <mpi.h>

namespace tem::distributed {

// True when this process was started by mpirun/mpiexec (Open MPI, MPICH or a PMI launcher),
// however many ranks.
bool launched_by_mpi();

// MPI_Init on construction (with threads funnelled through the main thread: TEM's OpenMP
// threads never call MPI), MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace tem::distributed
