#include "forces/system_energies.hpp"

#include "dynamics/integrator.hpp"

namespace tem {

Energies system_energies(const Model& model, const State& state) {
  return system_energies(model, state, nullptr);
}

Energies system_energies(const Model& model, const State& state, SolverSync* sync) {
  Energies e;
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    if (sync && !sync->owns(static_cast<int>(i))) continue;
    // Fixed bodies and bodies with a prescribed motion are driven from outside: their energy
    // is the driver's (State::driven_work counts what moving ones give the others), and a gate
    // taken away must not change the energy of what is left.
    if (model.bodies[i].driven()) continue;
    const RigidInertia& inertia = model.bodies[i].inertia;
    e.kinetic += kinetic_energy(inertia, state.bodies[i]);
    e.potential += potential_energy(inertia, model.scene.gravity, state.bodies[i]);
  }
  if (sync) {
    e.kinetic = sync->sum(e.kinetic);
    e.potential = sync->sum(e.potential);
  }
  return e;
}

}  // namespace tem
