// SEMM's quadratic against the integrators it claims to describe, and the solvers' answers on
// contacts worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/integrator.hpp"
#include "forces/body_response.hpp"
#include "forces/semm.hpp"
#include "forces/semm_paper/semm_paper.hpp"
#include "geometry/primitives.hpp"
#include "simulation/step.hpp"

namespace tem {
namespace test_semm {

BodyDef brick_body(const Vec3& position) {
  BodyDef b;
  b.name = "brick";
  b.shape.type = ShapeType::box;
  b.shape.size = Vec3(0.3, 0.2, 0.1);
  b.position = position;
  b.rotation = euler_zxz(0.3, 0.7, -0.2);
  b.velocity = Vec3(0.1, -0.2, 0.3);
  b.angular_velocity = Vec3(2.0, -1.0, 3.0);
  b.density = 2.5;
  return b;
}

// The paper's Omega' is affine in the torque N held through the step; its slope must be
// eq. 18 differentiated (with eq. 27's factor 3/2), checked against the integrator itself.
TEST(Semm, PaperTorqueResponseIsTheIntegratorsSlope) {
  SceneDef scene;
  scene.bodies.push_back(brick_body(Vec3::Zero()));
  const Model model = build_model(scene);
  BodyState s = initial_state(model).bodies[0];
  s.prev_torque = Vec3(0.01, 0.02, -0.03);
  s.has_prev_torque = true;
  const RigidInertia& inertia = model.bodies[0].inertia;
  const Real dt = 1e-3;
  const Mat3 slope = paper_torque_response(inertia, s, dt);
  BodyState base = s;
  integrate_paper(inertia, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), dt, base);
  for (int k = 0; k < 3; ++k) {
    BodyState pushed = s;
    const Vec3 torque = 1e-3 * Vec3::Unit(k);
    integrate_paper(inertia, Vec3::Zero(), Vec3::Zero(), torque, dt, pushed);
    // Affine: the difference is exact up to round-off of Omega (~|Omega| 1e-16).
    EXPECT_LT((pushed.omega - base.omega - slope * torque).norm(), 1e-12 * s.omega.norm())
        << "column " << k;
  }
  // At Omega = 0 the slope is 3/2 dt A^-1 g^T: eq. 27's factor.
  s.omega.setZero();
  EXPECT_LT((paper_torque_response(inertia, s, dt) -
             1.5 * dt * inertia.inertia_inv * s.g.transpose())
                .norm(),
            1e-15);
}

// What SEMM predicts for the next step's velocities (the pseudo velocities after the impulses)
// is what the integrator then produces, for both integrators: SEMM and the integrator never
// disagree.
TEST(Semm, PredictedVelocitiesAreTheIntegratorsForBothIntegrators) {
  for (IntegratorKind kind : {IntegratorKind::default_, IntegratorKind::paper}) {
    SceneDef scene;
    scene.integrator = kind;
    scene.time_step = 1e-3;
    scene.bodies.push_back(brick_body(Vec3::Zero()));
    const Model model = build_model(scene);
    const State state = initial_state(model);
    std::vector<BodyResponse> responses;
    body_responses(model, state, scene.time_step, responses);
    const BodyResponse& r = responses[0];
    // An arbitrary impulse: linear j, angular h, both world.
    const Vec3 j(0.02, -0.01, 0.03), h(0.001, 0.002, -0.0015);
    const Vec3 predicted_v = r.velocity + r.inverse_mass * j;
    BodyState s = state.bodies[0];
    integrate(kind, model.bodies[0].inertia, scene.gravity, j / scene.time_step,
              h / scene.time_step, scene.time_step, s);
    EXPECT_LT((s.v - predicted_v).norm(), 1e-13);
    const RigidInertia& in = model.bodies[0].inertia;
    const Real kinetic = 0.5 * s.omega.dot(in.inertia * s.omega);
    if (kind == IntegratorKind::default_) {
      // y is the world angular velocity after the kick; the drift keeps its kinetic energy.
      const Vec3 w = r.angular_velocity + r.angular * h;
      const Mat3 iw = state.bodies[0].g * in.inertia * state.bodies[0].g.transpose();
      EXPECT_NEAR(kinetic, 0.5 * w.dot(iw * w), 1e-13 * kinetic);
    } else {
      // y = W^T A Omega'; with W invertible, Omega' = (W^T A)^-1 y.
      const Mat3 w = paper_torque_response(in, state.bodies[0], scene.time_step) / scene.time_step;
      const Vec3 y = r.angular_velocity + r.angular * h;
      const Vec3 omega = (w.transpose() * in.inertia).inverse() * y;
      EXPECT_LT((omega - s.omega).norm(), 1e-10 * s.omega.norm())
          << omega.transpose() << " vs " << s.omega.transpose() << " y " << y.transpose();
    }
  }
}

// A unit mass (unit inverse inertia) sliding at (2, 0, -3) onto a fixed plane with friction mu,
// one contact point 0.5 below its centre of mass. By hand: the normal impulse stops the
// approach (3, no lever along the normal); sticking takes a tangential impulse of 2 / 1.25
// (effective mass 1/m + r^2/I along the slide), so friction gives min(1.6, 3 mu), on the wall
// along +x (the body's slide is -x relative to the wall).
TEST(Semm, SlidingImpactByHand) {
  for (Real mu : {0.0, 0.5, 1.0}) {
    std::vector<BodyResponse> bodies(1);
    bodies[0].inverse_mass = 1;
    bodies[0].angular = Mat3::Identity();
    bodies[0].velocity = Vec3(2, 0, -3);
    ContactPoint c{0, 0, -1, 0, Vec3::Zero(), Vec3(0, 0, -1), Vec3::UnitX(), Vec3::UnitY(), 0};
    c.tangent2 = c.normal.cross(c.tangent1);
    const std::vector<ContactPoint> points = {c};
    // Start relative velocity of the wall w.r.t. the body: normal -3 (approaching), slip -2.
    const std::vector<Real> start = {-3};
    std::vector<PatchFriction> patches(1);
    patches[0].first = 0;
    patches[0].last = 1;
    patches[0].body_a = 0;
    patches[0].normal = c.normal;
    patches[0].tangent1 = c.tangent1;
    patches[0].tangent2 = c.tangent2;
    patches[0].start_slip = Vec3(-2, 0, 0);
    SolverSettings settings;
    settings.friction = mu;
    std::vector<PointImpulse> impulses(1);
    const SolverReport report =
        solve_semm(points, start, bodies, {Vec3(0, 0, 0.5)}, settings, patches, impulses);
    EXPECT_TRUE(report.converged);
    EXPECT_NEAR(impulses[0].normal, 3, 1e-12);  // on the wall along -z, on the body +z
    EXPECT_NEAR(patches[0].t1, std::min(1.6, 3 * mu), 1e-9) << "mu " << mu;
    EXPECT_NEAR(patches[0].t2, 0, 1e-12);
    EXPECT_EQ(patches[0].twist, 0);  // one point: no reach for a twist
  }
}

// The paper's unconstrained solve pulls as readily as it pushes: a body leaving the plane is
// held back (a negative impulse), where the default's solve lets it go.
TEST(Semm, PaperSolveAdheresDefaultDoesNot) {
  std::vector<BodyResponse> bodies(1);
  bodies[0].inverse_mass = 0.5;
  bodies[0].angular = Mat3::Identity();
  bodies[0].velocity = Vec3(0, 0, 1);  // leaving the floor
  ContactPoint c{0, 0, -1, 4, Vec3::Zero(), Vec3(0, 0, -1), Vec3::UnitX(), Vec3::UnitY(), 0};
  c.tangent2 = c.normal.cross(c.tangent1);
  std::vector<PointImpulse> paper, semm(1);
  solve_semm_paper({c}, bodies, {Vec3(0, 0, 0.1)}, paper);
  EXPECT_NEAR(paper[0].normal, -2, 1e-12);  // M * 1 pulled back
  std::vector<PatchFriction> patch(1);
  patch[0].last = 1;
  patch[0].body_a = 0;
  solve_semm({c}, {-1}, bodies, {Vec3(0, 0, 0.1)}, SolverSettings{}, patch, semm);
  EXPECT_EQ(semm[0].normal, 0);
}

}  // namespace test_semm
}  // namespace tem
