// Time integration of one rigid body over one step (method.md §3).
//
// Both integrators take the same inputs: the body's gravity acceleration G, and the force F and
// torque N (world axes, torque about the centre of mass) of everything else acting over the
// step, e.g. contact forces. The paper's integrator is eqs. 13-18 as printed; the default one
// keeps the attitude a rotation and conserves energy and angular momentum of free rotation.
#pragma once

#include "dynamics/body_state.hpp"
#include "tem/scene_def.hpp"
#include "tem/types.hpp"

namespace tem {

// Eqs. 13-18 of the paper: second-order Taylor step of Omega using eqs. 17-18, explicit Euler
// for x and g (eq. 14, 16) and for v (eq. 15). g drifts away from a rotation (eq. 16).
void integrate_paper(const RigidInertia& body, const Vec3& gravity, const Vec3& force,
                     const Vec3& torque, Real dt, BodyState& state);

// The default: a kick (v and the world angular momentum take the step's impulses) followed by a
// drift (x exact under the constant acceleration G + F/M; free rotation by the energy-momentum
// conserving implicit-midpoint/Cayley scheme). g stays orthonormal to round-off.
void integrate_default(const RigidInertia& body, const Vec3& gravity, const Vec3& force,
                       const Vec3& torque, Real dt, BodyState& state);

inline void integrate(IntegratorKind kind, const RigidInertia& body, const Vec3& gravity,
                      const Vec3& force, const Vec3& torque, Real dt, BodyState& state) {
  if (kind == IntegratorKind::paper)
    integrate_paper(body, gravity, force, torque, dt, state);
  else
    integrate_default(body, gravity, force, torque, dt, state);
}

// Energies of one body: kinetic 1/2 M v^2 + 1/2 Omega.A Omega, potential -M G.x.
Real kinetic_energy(const RigidInertia& body, const BodyState& state);
Real potential_energy(const RigidInertia& body, const Vec3& gravity, const BodyState& state);
// World angular momentum about the centre of mass, L = g A Omega.
Vec3 angular_momentum(const RigidInertia& body, const BodyState& state);

}  // namespace tem
