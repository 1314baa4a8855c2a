#include "forces/body_response.hpp"

#include "support/parallel.hpp"

#include "dynamics/integrator.hpp"

namespace tem {

Mat3 paper_torque_response(const RigidInertia& body, const BodyState& state, Real dt) {
  // Omega' = Omega + dOmega dt + 1/2 ddOmega dt^2 with, by eqs. 17-18 differentiated in N:
  //   d dOmega  = A^-1 g^T
  //   d ddOmega = A^-1 (R(Omega)^T g^T + g^T / dt + R(A Omega) A^-1 g^T - R(Omega) g^T)
  //   (R(Omega)^T = -R(Omega), so the Omega terms add to -2 R(Omega) g^T).
  // (dOmega x A Omega = -R(A Omega) dOmega; Omega x A dOmega = R(Omega) A dOmega).
  const Mat3& a_inv = body.inertia_inv;
  const Mat3 w = cross_matrix(state.omega);
  const Mat3 aw = cross_matrix(body.inertia * state.omega);
  // The g^T / dt term is eq. 18's torque rate dN = (N - N_prev) / dt; on a body's first step
  // there is no N_prev and the integrator takes dN = 0, so the factor is 1 there, 3/2 after.
  const Real rate = state.has_prev_torque ? 0.5 : 0.0;
  const Mat3 inner = (1 + rate) * dt * Mat3::Identity() - dt * dt * w + 0.5 * dt * dt * aw * a_inv;
  return a_inv * inner * state.g.transpose();
}

void body_responses(const Model& model, const State& state, Real dt,
                    std::vector<BodyResponse>& out, const ExternalLoads* loads) {
  const Vec3& gravity = model.scene.gravity;
  const bool loaded = loads && !loads->empty();
  out.assign(model.bodies.size(), BodyResponse{});
  parallel_for(static_cast<long long>(model.bodies.size()), 256, [&](long long i) {
    const Body& body = model.bodies[i];
    if (body.fixed) return;  // does not move: no response, no velocity
    const BodyState& s = state.bodies[i];
    if (body.motion) {  // moves as told (process/motion.hpp): no response, its own velocity
      out[i].driven = true;
      out[i].velocity = s.v;
      out[i].angular_velocity = s.g * s.omega;
      return;
    }
    const RigidInertia& inertia = body.inertia;
    BodyResponse& r = out[i];
    r.inverse_mass = 1 / inertia.mass;
    const Vec3 force = loaded ? loads->force[i] : Vec3::Zero();
    const Vec3 torque = loaded ? loads->torque[i] : Vec3::Zero();
    r.velocity = s.v + (gravity + force / inertia.mass) * dt;
    r.start_velocity = s.v;
    if (model.scene.integrator == IntegratorKind::paper) {
      // Omega' with no contact torque (the previous torque still enters through dN), and
      // W = (d Omega' / d N) / dt for an angular impulse h = N dt.
      BodyState free = s;
      integrate_paper(inertia, gravity, force, torque, dt, free);
      const Mat3 w = paper_torque_response(inertia, s, dt) / dt;
      r.angular = w.transpose() * inertia.inertia * w;
      r.angular_velocity = w.transpose() * (inertia.inertia * free.omega);
    } else {
      // W = A^-1 g^T: y is the world angular velocity, Q = g A^-1 g^T.
      // The external torque is an angular impulse N dt taken like a contact's.
      r.angular = s.g * inertia.inertia_inv * s.g.transpose();
      r.angular_velocity = s.g * s.omega + r.angular * (torque * dt);
    }
  });
}

}  // namespace tem
