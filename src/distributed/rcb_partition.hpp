// Who owns which part of space: recursive coordinate bisection (RCB) of the bodies' centres,
// weighted by each body's cost, through Zoltan (Trilinos, Debian's libtrilinos-zoltan-dev).
// Zoltan keeps the cuts, so between two balancings the owner of a body is the rank whose box
// holds its centre (owner_of), found without any message.
#pragma once

#include <mpi.h>

#include <memory>
#include <vector>

#include "tem/types.hpp"

struct Zoltan_Struct;

namespace tem::distributed {

class RcbPartition {
 public:
  explicit RcbPartition(MPI_Comm comm);
  ~RcbPartition();
  RcbPartition(const RcbPartition&) = delete;
  RcbPartition& operator=(const RcbPartition&) = delete;

  // New cuts for the bodies this rank owns (global ids, centres, costs > 0); every rank calls
  // it together. Returns the new owner of each of them.
  std::vector<int> balance(const std::vector<int>& ids, const std::vector<Vec3>& centres,
                           const std::vector<double>& costs);

  // The rank whose box holds `point`, by the cuts of the last balance().
  int owner_of(const Vec3& point) const;

 private:
  struct Input {
    const std::vector<int>* ids = nullptr;
    const std::vector<Vec3>* centres = nullptr;
    const std::vector<double>* costs = nullptr;
  };
  Zoltan_Struct* zoltan_ = nullptr;
  std::unique_ptr<Input> input_;
  int rank_ = 0;
};

}  // namespace tem::distributed
