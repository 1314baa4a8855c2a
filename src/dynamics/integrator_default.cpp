// The default integrator: a kick, then a drift on the rotation group.
//
// Why not the paper's eqs. 13-18? Eq. 16, g' = g (I + dt R(Omega)), leaves the rotation group:
// each step scales the plane across Omega by sqrt(1 + (|Omega| dt)^2), and over the hundreds of
// thousands of steps of a settling body that visibly shears and inflates it. Its Taylor step for
// Omega (eq. 13) conserves neither the kinetic energy nor the angular momentum of free rotation,
// so a tumbling body slowly gains or loses spin. This scheme fixes both and stays second order.
//
// Kick. The step's impulses change the momenta: v+ = v + (G + F/M) dt, and the world angular
// momentum L+ = g A Omega + N dt. Writing the torque as an impulse on L (not on Omega) is what
// makes a constant torque give L exactly L0 + N t.
//
// Drift. x' = x + dt v+ - 1/2 dt^2 (G + F/M) is exact under a constant acceleration (the kick
// added the whole (G + F/M) dt to v; the correction puts the parabola back). The rotation is
// torque-free over the step, advanced by the implicit midpoint rule on the body-frame momentum L_b = g^T L+:
//   L_b' = L_b - dt Omega_m x (L_b + L_b')/2,   Omega_m = A^-1 (L_b + L_b')/2,
// which is L_b' = cay(-dt R(Omega_m)) L_b with the Cayley transform
// cay(W) = (I - W/2)^-1 (I + W/2), a rotation for every skew W. The attitude follows the
// same rotation the other way, g' = g cay(dt R(Omega_m)), so that
//   - world momentum is conserved exactly: g' L_b' = g cay(W) cay(-W) L_b = g L_b;
//   - the kinetic energy 1/2 L_b.A^-1 L_b is conserved exactly: it is a quadratic invariant of
//     Euler's equations, and the implicit midpoint rule keeps every quadratic invariant;
//   - g stays a rotation (a Lie-group step), up to round-off, which one polar (Newton-Schulz)
//     step per step removes.
// The midpoint rule is symmetric, hence second order; with E and |L| both kept, the discrete
// body-frame momentum stays on the exact polhode, so the intermediate-axis (Dzhanibekov) flip
// comes out with its right period (tests/test_integrators.cpp checks it against RK4 and the
// elliptic-integral closed form).
//
// Why this matters for contact: SEMM (method.md §6) chooses contact impulses that minimise the
// system's energy at step n+1. The kick is linear in the impulses, so the kinetic energy reached
// after the kick is quadratic in them, and because the drift conserves that kinetic energy
// exactly, the energy at n+1 is that same quadratic. An integrator whose drift changed the
// energy would make SEMM's objective non-quadratic.
//
// Omega_m is found by fixed-point iteration from the explicit guess A^-1 L_b. The map contracts
// by about |Omega| dt (times the inertia's anisotropy), so for |Omega| dt ~ 1e-3 five iterations
// reach round-off.
#include "dynamics/integrator.hpp"

namespace tem {

namespace {

constexpr int kMaxMidpointIterations = 100;
constexpr Real kMidpointTolerance = 1e-15;  // relative change of Omega_m

// cay(R(a)) b without forming the matrix: b plus a small increment, which keeps |b| to round-off
// better than multiplying by a matrix whose diagonal is 1 - O(|a|^2).
Vec3 cayley_apply(const Vec3& a, const Vec3& b) {
  const Vec3 ab = a.cross(b);
  return b + (4 / (4 + a.squaredNorm())) * (ab + 0.5 * a.cross(ab));
}

// One Newton-Schulz step towards the polar factor, g + g (I - g^T g)/2: the nearest rotation to
// second order in g's departure from one, which is round-off here. Written as a correction, not
// as g (3I - g^T g)/2, because 3 - (1 + e) rounds e to multiples of 4.4e-16, and that bias alone
// made |L| shrink by ~1e-16 per step.
Mat3 orthonormalised(const Mat3& g) { return g + 0.5 * g * (Mat3::Identity() - g.transpose() * g); }

}  // namespace

void integrate_default(const RigidInertia& body, const Vec3& gravity, const Vec3& force,
                       const Vec3& torque, Real dt, BodyState& state) {
  const Mat3& a = body.inertia;          // A
  const Mat3& a_inv = body.inertia_inv;  // A^-1

  // Kick: the step's impulses on the linear and the world angular momentum.
  const Vec3 v_kicked = state.v + (gravity + force / body.mass) * dt;
  const Vec3 l_kicked = state.g * (a * state.omega) + torque * dt;

  // Drift of the centre of mass, exact for a constant acceleration G + F/M over the step. The
  // contact force is taken as acting through the step like gravity, not as a blow at its start:
  // a body resting on the floor (F = -M G) then stays exactly where it is, where a blow would
  // lift it by G dt^2 / 2 every step.
  state.x += dt * v_kicked - 0.5 * dt * dt * (gravity + force / body.mass);
  state.v = v_kicked;

  // Drift of the rotation: implicit midpoint on L_b, solved for Omega_m by fixed point.
  const Vec3 l_body = state.g.transpose() * l_kicked;  // L_b = g^T L+ (g is a rotation)
  Vec3 omega_mid = a_inv * l_body;
  for (int it = 0; it < kMaxMidpointIterations; ++it) {
    const Vec3 l_body_next = cayley_apply(-dt * omega_mid, l_body);
    const Vec3 omega_next = a_inv * (0.5 * (l_body + l_body_next));
    const Real change = (omega_next - omega_mid).norm();
    omega_mid = omega_next;
    if (change <= kMidpointTolerance * omega_mid.norm()) break;
  }

  // L_b' and g' from the same Omega_m, so that g' L_b' = g L_b to round-off.
  const Vec3 l_body_next = cayley_apply(-dt * omega_mid, l_body);
  state.g = orthonormalised(state.g * cayley(dt * omega_mid));
  state.omega = a_inv * l_body_next;

  // Not used here; kept so that switching to the paper's integrator mid-run has its dN.
  state.prev_torque = torque;
  state.has_prev_torque = true;
}

}  // namespace tem
