// The belt's energy check shared by the process and sub-step tests: over `steps` steps the
// energy less the work the driven bodies did never rises beyond round-off of m v^2 of the
// carried block, and the belt does put work in.
#pragma once

#include <gtest/gtest.h>

#include "tem/simulation.hpp"

namespace tem::testing_support {

inline void expect_energy_less_driven_work_never_rises(Simulation& sim, int steps) {
  const SystemEnergies start = sim.energies();
  Real last = start.total() - start.driven_work;
  const Real scale = sim.mass(sim.body_index("block")) * 400;  // m v^2
  for (int k = 0; k < steps; ++k) {
    sim.step();
    const SystemEnergies e = sim.energies();
    const Real now = e.total() - e.driven_work;
    EXPECT_LE(now, last + 1e-12 * scale) << "step " << k;
    last = now;
  }
  EXPECT_GT(sim.energies().driven_work, 0);
}

}  // namespace tem::testing_support
