// How each body's next-step velocities answer the step's contact impulses, as SEMM needs it
// (method.md §6): the energy the contact forces minimise is a quadratic in them, and this is
// that quadratic, taken from the integrator actually used so that the two never disagree.
//
// Both integrators make the next step's velocities affine in the contact impulses: the linear
// one v' = v + G dt + P/M, the angular one Omega' = Omega_free + W h for an angular impulse h
// (world axes). The energy at n+1 that the impulses can change is the kinetic energy
// T = 1/2 M |v'|^2 + 1/2 Omega'.A Omega' (the paper's integrator moves x with the old v, so the
// potential energy at n+1 does not depend on them; the default's drift keeps the kinetic
// energy reached by the kick, so T is the energy after the whole step). Its gradient with
// respect to an impulse J^T lambda is J y with the "pseudo velocity" y = W^T A Omega' (and v'
// for the linear part), and its Hessian J Q J^T with Q = W^T A W. With the default integrator
// W = A^-1 g^T, so y is the world angular velocity and Q the world inverse inertia; with the
// paper's, W carries eq. 18's torque-rate term, which gives eq. 27's factor 3/2.
#pragma once

#include <vector>

#include "world/model.hpp"

namespace tem {

struct BodyResponse {
  Real inverse_mass = 0;               // 0 for a fixed body
  bool driven = false;                 // prescribed motion: no response, a velocity of its own
  Mat3 angular = Mat3::Zero();         // Q: angular impulse (world) -> pseudo angular velocity
  Vec3 velocity = Vec3::Zero();        // y, linear part, with no contact impulse: v + G dt
  Vec3 angular_velocity = Vec3::Zero();  // y, angular part, with no contact impulse
  // The linear velocity at the start of the step: what y's linear part is for a body the
  // contacts hold as it was (SEMM by Newton's warm start of a resting pile).
  Vec3 start_velocity = Vec3::Zero();
};

// A body's pseudo velocity (y) in the row solver while it sweeps, linear and angular together
// in one cache line of their own. Why: the threads that share a colour's patches update
// different bodies, but in two flat arrays of Vec3 neighbouring bodies share lines, which then
// went back and forth between the cores at nearly every patch; one line per body also serves a
// row's two reads of a body with one.
struct alignas(64) SlotVelocity {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
};

// Responses of every body for one step of `dt` from `state`, under gravity and the external
// loads (none when null or empty).
void body_responses(const Model& model, const State& state, Real dt,
                    std::vector<BodyResponse>& out, const ExternalLoads* loads = nullptr);

// Velocity of body `body`'s material point at p in `state` (a wall, body -1, and fixed bodies
// stand still).
inline Vec3 material_point_velocity(const Model& model, const State& state, int body,
                                    const Vec3& p) {
  if (body < 0 || model.bodies[body].fixed) return Vec3::Zero();
  const BodyState& s = state.bodies[body];
  return s.v + s.angular_velocity_world().cross(p - s.x);
}

// The velocity at which body `body`'s surface slides at time t (a conveyor belt's
// `motion.surface_velocity` inside its window), zero for walls and every other body.
inline Vec3 surface_velocity(const Model& model, int body, Real t) {
  if (body < 0) return Vec3::Zero();
  const std::optional<MotionDef>& m = model.bodies[body].motion;
  if (!m || !m->surface_velocity || t < m->start || !(t < m->end)) return Vec3::Zero();
  return *m->surface_velocity;
}

// Adds a contact force `on_b` acting at `at` (and a pure moment) to body B, and their opposites
// to body A, as forces and torques about the centres of mass `centres`; walls (body -1) take
// nothing. Fixed and driven bodies take theirs too (force sensors read them; the integration
// leaves such bodies where they are told to be).
inline void add_contact_force(const std::vector<Vec3>& centres, int body_a, int body_b,
                              const Vec3& at, const Vec3& on_b, const Vec3& moment,
                              std::vector<Vec3>& force, std::vector<Vec3>& torque) {
  force[body_a] -= on_b;
  torque[body_a] -= (at - centres[body_a]).cross(on_b) + moment;
  if (body_b >= 0) {
    force[body_b] += on_b;
    torque[body_b] += (at - centres[body_b]).cross(on_b) + moment;
  }
}

// d Omega' / d N of the paper's update (eqs. 13, 17, 18) for a torque N held through the step:
// A^-1 [3/2 dt I - dt^2 R(Omega) + 1/2 dt^2 R(A Omega) A^-1] g^T, with 1 for 3/2 on a body's
// first step (no previous torque, no torque rate).
Mat3 paper_torque_response(const RigidInertia& body, const BodyState& state, Real dt);

}  // namespace tem
