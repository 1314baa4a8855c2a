// How many steps an output interval spans (output.interval, output.checkpoint_interval): the
// nearest whole number, at least one. The one-process run and the run over MPI ranks both
// count their rows and checkpoints by it.
#pragma once

#include <algorithm>
#include <cmath>

#include "tem/types.hpp"

namespace tem {

inline long long steps_per(Real interval, Real dt) {
  return std::max<long long>(1, std::llround(interval / dt));
}

}  // namespace tem
