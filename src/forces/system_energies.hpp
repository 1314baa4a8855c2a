// Whole-system energies at a state, of the bodies that move freely: what SEMM's rule "never add
// energy" and the overlap correction's budget are measured in, and what energy.csv reports.
// Here, beside the solvers that use it, because over MPI ranks the sum goes through their
// SolverSync.
#pragma once

#include "forces/solver_sync.hpp"
#include "world/model.hpp"

namespace tem {

// Kinetic, potential (-M G.x summed), their total.
struct Energies {
  Real kinetic = 0;
  Real potential = 0;
  Real total() const { return kinetic + potential; }
};
Energies system_energies(const Model& model, const State& state);
// Over MPI ranks (sync not null): each rank's owned bodies, summed over the ranks.
Energies system_energies(const Model& model, const State& state, SolverSync* sync);

}  // namespace tem
