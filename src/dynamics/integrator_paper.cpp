// The paper's integrator, eqs. 13-18 exactly as printed (method.md §3).
//
// Omega takes a second-order Taylor step whose derivatives come from Euler's equations in body
// axes (eqs. 17-18); x, v and the attitude g take explicit Euler steps (eqs. 14-16). Every
// right-hand side uses the state at the start of the step. Eq. 16 does not keep g a rotation:
// g (I + dt R(Omega)) scales the plane across Omega by sqrt(1 + (|Omega| dt)^2) per step. Paper
// mode keeps that drift on purpose so that the paper's runs can be reproduced; the default
// integrator (integrator_default.cpp) is the one that stays on the rotation group. For the same
// reason g^T, not g^-1, takes world vectors to body axes, as the paper prints it.
#include "dynamics/integrator.hpp"

namespace tem {

void integrate_paper(const RigidInertia& body, const Vec3& gravity, const Vec3& force,
                     const Vec3& torque, Real dt, BodyState& state) {
  const Mat3& a = body.inertia;          // A
  const Mat3& a_inv = body.inertia_inv;  // A^-1
  const Mat3 g = state.g;
  const Vec3 omega = state.omega;

  // dN = (N^n - N^{n-1}) / dt; no previous torque on the first step, so no torque rate.
  const Vec3 torque_rate =
      state.has_prev_torque ? Vec3((torque - state.prev_torque) / dt) : Vec3::Zero();
  const Vec3 torque_body = g.transpose() * torque;  // g^T N
  const Vec3 a_omega = a * omega;                   // A Omega

  // eq. 17: dOmega = A^-1 (g^T N - Omega x A Omega)
  const Vec3 d_omega = a_inv * (torque_body - omega.cross(a_omega));
  // eq. 18: ddOmega = A^-1 (R(Omega)^T g^T N + g^T dN - dOmega x A Omega - Omega x A dOmega)
  const Vec3 dd_omega =
      a_inv * (cross_matrix(omega).transpose() * torque_body + g.transpose() * torque_rate -
               d_omega.cross(a_omega) - omega.cross(a * d_omega));

  state.omega = omega + d_omega * dt + 0.5 * dd_omega * dt * dt;  // eq. 13
  state.x += state.v * dt;                                        // eq. 14 (old v)
  state.v += (gravity + force / body.mass) * dt;                  // eq. 15
  state.g = g + g * cross_matrix(omega) * dt;                     // eq. 16 (old Omega)

  // N^{n-1} of the next step's eq. 18.
  state.prev_torque = torque;
  state.has_prev_torque = true;
}

}  // namespace tem
