// Energies and angular momentum of one body, the quantities the integrators must keep and the
// observers report (method.md §3).
#include "dynamics/integrator.hpp"

namespace tem {

// 1/2 M |v|^2 + 1/2 Omega.A Omega; the rotational part is frame-free, so body axes suffice.
Real kinetic_energy(const RigidInertia& body, const BodyState& state) {
  return 0.5 * body.mass * state.v.squaredNorm() +
         0.5 * state.omega.dot(body.inertia * state.omega);
}

// -M G.x: zero at the world origin, growing against gravity.
Real potential_energy(const RigidInertia& body, const Vec3& gravity, const BodyState& state) {
  return -body.mass * gravity.dot(state.x);
}

// L = g A Omega, world axes, about the centre of mass.
Vec3 angular_momentum(const RigidInertia& body, const BodyState& state) {
  return state.g * (body.inertia * state.omega);
}

}  // namespace tem
