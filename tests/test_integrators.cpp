// Tests of the two integrators (method.md §3) against closed forms and against references
// computed here: RK4 on Euler's equations in principal axes, the elliptic-integral period of
// torque-free tumbling, and the exact powers of eq. 16's matrix. No expected number is copied
// from a run. Measured figures are printed and recorded as test properties so that they can be
// quoted (docs, issue reports).
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "dynamics/integrator.hpp"

namespace tem {
namespace test_integrators {

// A brick (box) of sides a, b, c along its principal axes and mass M: principal moments
// M(b^2+c^2)/12, M(a^2+c^2)/12, M(a^2+b^2)/12. The principal axes are the columns of `axes` in
// the body frame, so A = Q diag(I) Q^T is a full tensor unless Q = I; A^-1 is formed the same way
// from 1/I, independently of any matrix inverse.
struct Brick {
  Vec3 moments;
  Mat3 axes;
  RigidInertia body;

  Vec3 to_principal(const Vec3& body_vector) const { return axes.transpose() * body_vector; }
  Vec3 from_principal(const Vec3& principal) const { return axes * principal; }
};

Brick make_brick(Real mass, Real a, Real b, Real c, const Mat3& axes = Mat3::Identity()) {
  Brick brick;
  brick.moments = Vec3(b * b + c * c, a * a + c * c, a * a + b * b) * (mass / 12);
  brick.axes = axes;
  brick.body.mass = mass;
  brick.body.inertia = axes * brick.moments.asDiagonal() * axes.transpose();
  brick.body.inertia_inv = axes * brick.moments.cwiseInverse().asDiagonal() * axes.transpose();
  return brick;
}

// A fixed generic rotation, for tilted principal axes and initial attitudes.
Mat3 generic_rotation(Real angle, const Vec3& axis) {
  return Eigen::AngleAxis<Real>(angle, axis.normalized()).toRotationMatrix();
}

// Euler's equations in principal axes, I1 w1' = (I2 - I3) w2 w3 and cyclic; this is
// A dOmega/dt = -Omega x A Omega written out component by component.
Vec3 euler_rate(const Vec3& moments, const Vec3& w) {
  const Vec3& i = moments;
  return Vec3((i.y() - i.z()) * w.y() * w.z() / i.x(), (i.z() - i.x()) * w.z() * w.x() / i.y(),
              (i.x() - i.y()) * w.x() * w.y() / i.z());
}

// Classical fourth-order Runge-Kutta step of euler_rate.
Vec3 rk4_step(const Vec3& moments, const Vec3& w, Real h) {
  const Vec3 k1 = euler_rate(moments, w);
  const Vec3 k2 = euler_rate(moments, w + 0.5 * h * k1);
  const Vec3 k3 = euler_rate(moments, w + 0.5 * h * k2);
  const Vec3 k4 = euler_rate(moments, w + h * k3);
  return w + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
}

// Times at which a sampled signal changes sign, linearly interpolated between samples.
class SignChanges {
 public:
  void add(Real t, Real y) {
    if (started_ && ((y_ < 0 && y >= 0) || (y_ > 0 && y <= 0)))
      times_.push_back(t_ + (t - t_) * y_ / (y_ - y));
    started_ = true;
    t_ = t;
    y_ = y;
  }
  int count() const { return static_cast<int>(times_.size()); }
  // Mean time between successive sign changes.
  Real mean_interval() const { return (times_.back() - times_.front()) / (count() - 1); }

 private:
  bool started_ = false;
  Real t_ = 0;
  Real y_ = 0;
  std::vector<Real> times_;
};

// The largest |entry| of g^T g - I: how far g is from orthonormal.
Real orthonormality_error(const Mat3& g) {
  return (g.transpose() * g - Mat3::Identity()).cwiseAbs().maxCoeff();
}

void report(const std::string& key, Real value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  std::cout << "[ measured ] " << key << " = " << text << "\n";
  ::testing::Test::RecordProperty(key, text);
}

Vec3 earth_gravity() { return Vec3(0, 0, -9.81); }

// a. Free fall: the default integrator is exact under constant gravity (and a constant force,
// which acts through the step as gravity does), and keeps the total energy exactly.
TEST(IntegratorDefault, FreeFallIsExact) {
  const Brick brick = make_brick(2.5, 0.4, 0.3, 0.2);
  const Vec3 x0(1.0, -2.0, 30.0), v0(3.0, 0.5, 4.0);
  const Real dt = 1e-3;
  const int n = 1000;
  const Real t = n * dt;

  BodyState s;
  s.x = x0;
  s.v = v0;
  const Real e0 = kinetic_energy(brick.body, s) + potential_energy(brick.body, earth_gravity(), s);
  for (int k = 0; k < n; ++k)
    integrate_default(brick.body, earth_gravity(), Vec3::Zero(), Vec3::Zero(), dt, s);
  const Vec3 x_exact = x0 + v0 * t + 0.5 * earth_gravity() * t * t;
  const Vec3 v_exact = v0 + earth_gravity() * t;
  EXPECT_LE((s.x - x_exact).norm(), 1e-12 * x_exact.norm());
  EXPECT_LE((s.v - v_exact).norm(), 1e-12 * v_exact.norm());
  // The kick's energy gain M v.G dt + 1/2 M G^2 dt^2 is exactly the drift's potential loss.
  const Real e = kinetic_energy(brick.body, s) + potential_energy(brick.body, earth_gravity(), s);
  const Real energy_scale =
      brick.body.mass * (v0.squaredNorm() + earth_gravity().norm() * x0.norm());
  EXPECT_LE(std::abs(e - e0), 1e-12 * energy_scale);

  // With a constant force F as well: x_n = x0 + v0 t + 1/2 (G + F/M) t^2.
  const Vec3 force(0.4, -0.3, 1.2);
  s = BodyState();
  s.x = x0;
  s.v = v0;
  for (int k = 0; k < n; ++k)
    integrate_default(brick.body, earth_gravity(), force, Vec3::Zero(), dt, s);
  const Vec3 f_over_m = force / brick.body.mass;
  const Vec3 x_forced = x_exact + 0.5 * f_over_m * t * t;
  const Vec3 v_forced = v_exact + f_over_m * t;
  EXPECT_LE((s.x - x_forced).norm(), 1e-12 * x_forced.norm());
  EXPECT_LE((s.v - v_forced).norm(), 1e-12 * v_forced.norm());
}

// a. Free fall, paper: eq. 14 is explicit Euler with the old v, so
// x_n = x0 + v0 t + G dt^2 n(n-1)/2, while eq. 15 makes v exact.
TEST(IntegratorPaper, FreeFallIsExplicitEuler) {
  const Brick brick = make_brick(2.5, 0.4, 0.3, 0.2);
  const Vec3 x0(1.0, -2.0, 30.0), v0(3.0, 0.5, 4.0);
  const Real dt = 1e-3;
  const int n = 1000;
  const Real t = n * dt;

  BodyState s;
  s.x = x0;
  s.v = v0;
  for (int k = 0; k < n; ++k)
    integrate_paper(brick.body, earth_gravity(), Vec3::Zero(), Vec3::Zero(), dt, s);
  const Vec3 x_euler = x0 + v0 * t + earth_gravity() * dt * dt * (0.5 * n * (n - 1.0));
  const Vec3 v_exact = v0 + earth_gravity() * t;
  EXPECT_LE((s.x - x_euler).norm(), 1e-12 * x_euler.norm());
  EXPECT_LE((s.v - v_exact).norm(), 1e-12 * v_exact.norm());
}

// The observers against closed forms in principal axes.
TEST(Energy, MatchesClosedForms) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3, generic_rotation(0.7, Vec3(1, 2, 3)));
  const Vec3 w_principal(0.3, -1.1, 0.7);
  BodyState s;
  s.x = Vec3(0.5, -1.5, 2.0);
  s.v = Vec3(1.0, 2.0, -0.5);
  s.g = generic_rotation(1.3, Vec3(-2, 1, 0.5));
  s.omega = brick.from_principal(w_principal);

  const Real m = brick.body.mass;
  const Vec3 i = brick.moments;
  const Real rotational =
      0.5 * (i.x() * w_principal.x() * w_principal.x() + i.y() * w_principal.y() * w_principal.y() +
             i.z() * w_principal.z() * w_principal.z());
  const Real translational = 0.5 * m * (1.0 + 4.0 + 0.25);
  EXPECT_NEAR(kinetic_energy(brick.body, s), translational + rotational, 1e-14);
  EXPECT_NEAR(potential_energy(brick.body, earth_gravity(), s), m * 9.81 * 2.0, 1e-13);
  const Vec3 l_exact = s.g * brick.axes * i.cwiseProduct(w_principal);
  EXPECT_LE((angular_momentum(brick.body, s) - l_exact).norm(), 1e-14 * l_exact.norm());
}

// b. Torque-free tumbling with the default integrator: kinetic energy and world angular
// momentum are kept, and g stays a rotation.
TEST(IntegratorDefault, TumblingKeepsEnergyMomentumAndRotation) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3, generic_rotation(0.7, Vec3(1, 2, 3)));
  BodyState s;
  s.g = generic_rotation(1.3, Vec3(-2, 1, 0.5));
  s.omega = Vec3(0.3, -1.1, 0.7).normalized() * 2.0;  // generic, body axes
  const Real dt = 1e-3 / s.omega.norm();              // |Omega| dt = 1e-3
  const int n = 100000;

  const Real e0 = kinetic_energy(brick.body, s);
  const Vec3 l0 = angular_momentum(brick.body, s);
  Real energy_drift = 0, momentum_drift = 0, orthonormality = 0, det_error = 0;
  for (int k = 0; k < n; ++k) {
    integrate_default(brick.body, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), dt, s);
    energy_drift = std::max(energy_drift, std::abs(kinetic_energy(brick.body, s) - e0) / e0);
    momentum_drift =
        std::max(momentum_drift, (angular_momentum(brick.body, s) - l0).norm() / l0.norm());
    orthonormality = std::max(orthonormality, orthonormality_error(s.g));
    det_error = std::max(det_error, std::abs(s.g.determinant() - 1));
  }
  report("tumbling_energy_drift_max", energy_drift);
  report("tumbling_momentum_drift_max", momentum_drift);
  report("tumbling_orthonormality_max", orthonormality);
  report("tumbling_det_error_max", det_error);
  EXPECT_LT(energy_drift, 1e-6);
  EXPECT_LT(momentum_drift, 1e-6);
  EXPECT_LT(orthonormality, 1e-12);
  EXPECT_LT(det_error, 1e-12);
}

// Half-period of the intermediate-axis component in torque-free motion (I1 < I2 < I3), i.e.
// the time between flips: 2K(k)/rate with the Jacobi-elliptic solution (Landau & Lifshitz,
// Mechanics §37), for |L|^2 above or below 2E I2.
Real flip_interval_closed_form(const Vec3& i, const Vec3& w) {
  const Real two_e = i.dot(w.cwiseProduct(w));
  const Real l2 = i.cwiseProduct(w).squaredNorm();
  const Real i1 = i.x(), i2 = i.y(), i3 = i.z();
  Real rate, k2;
  if (l2 > two_e * i2) {  // the polhode circles the axis of I3
    rate = std::sqrt((i3 - i2) * (l2 - two_e * i1) / (i1 * i2 * i3));
    k2 = (i2 - i1) * (two_e * i3 - l2) / ((i3 - i2) * (l2 - two_e * i1));
  } else {  // ... or the axis of I1
    rate = std::sqrt((i2 - i1) * (two_e * i3 - l2) / (i1 * i2 * i3));
    k2 = (i3 - i2) * (l2 - two_e * i1) / ((i2 - i1) * (two_e * i3 - l2));
  }
  return 2 * std::comp_ellint_1(std::sqrt(k2)) / rate;
}

// c. The Dzhanibekov flip: spin about the intermediate axis with a small perturbation. The
// time between flips from the default integrator must match RK4 (10x smaller step) and the
// closed form.
TEST(IntegratorDefault, ReproducesDzhanibekovFlipPeriod) {
  // Sides 3, 2, 1 and M = 12: moments 5 < 10 < 13, principal axes tilted in the body frame.
  const Brick brick = make_brick(12.0, 3.0, 2.0, 1.0, generic_rotation(0.7, Vec3(1, 2, 3)));
  ASSERT_LT(brick.moments.x(), brick.moments.y());
  ASSERT_LT(brick.moments.y(), brick.moments.z());
  const Vec3 w0 = Vec3(1e-2, 1.0, 1e-2).normalized();  // principal axes, |Omega| = 1
  const Real dt = 1e-3;                                // |Omega| dt = 1e-3
  const int flips = 4;                                 // sign changes, 3 intervals averaged

  BodyState s;
  s.omega = brick.from_principal(w0);
  SignChanges tem;
  tem.add(0, w0.y());
  for (int k = 1; k <= 150000 && tem.count() < flips; ++k) {
    integrate_default(brick.body, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), dt, s);
    tem.add(k * dt, brick.to_principal(s.omega).y());
  }
  ASSERT_EQ(tem.count(), flips);

  const Real h = dt / 10;
  Vec3 w = w0;
  SignChanges rk4;
  rk4.add(0, w.y());
  for (int k = 1; k <= 1500000 && rk4.count() < flips; ++k) {
    w = rk4_step(brick.moments, w, h);
    rk4.add(k * h, w.y());
  }
  ASSERT_EQ(rk4.count(), flips);

  const Real closed = flip_interval_closed_form(brick.moments, w0);
  const Real vs_rk4 = std::abs(tem.mean_interval() - rk4.mean_interval()) / rk4.mean_interval();
  const Real vs_closed = std::abs(tem.mean_interval() - closed) / closed;
  report("flip_interval_tem", tem.mean_interval());
  report("flip_interval_rk4", rk4.mean_interval());
  report("flip_interval_closed_form", closed);
  report("flip_interval_tem_vs_rk4", vs_rk4);
  report("flip_interval_tem_vs_closed_form", vs_closed);
  EXPECT_LT(vs_rk4, 5e-3);
  EXPECT_LT(vs_closed, 5e-3);
  // The two references agree far more closely, which checks the references themselves.
  EXPECT_LT(std::abs(rk4.mean_interval() - closed) / closed, 1e-6);
}

// d. Eq. 16's drift: spinning about a principal axis, Omega stays constant under eqs. 13, 17, 18
// and g_n = g_0 (I + dt R(Omega))^n, whose singular values are 1 along Omega and
// (1 + (|Omega| dt)^2)^(n/2) across it.
TEST(IntegratorPaper, AttitudeDriftMatchesEq16) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3);  // largest moment about z: stable spin
  const Real spin = 2.0;
  const Vec3 omega0(0, 0, spin);
  const Real dt = 1e-3 / spin;  // |Omega| dt = 1e-3
  const int n = 100000;

  BodyState s;
  s.g = generic_rotation(1.3, Vec3(-2, 1, 0.5));
  s.omega = omega0;
  const Mat3 g0 = s.g;
  for (int k = 0; k < n; ++k)
    integrate_paper(brick.body, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), dt, s);
  EXPECT_EQ(s.omega, omega0);  // exactly: Omega x A Omega vanishes term by term

  const Real across = std::pow(1 + (spin * dt) * (spin * dt), 0.5 * n);
  const Vec3 singular = Eigen::JacobiSVD<Mat3>(s.g).singularValues();  // descending
  EXPECT_NEAR(singular(0) / across, 1, 1e-9);
  EXPECT_NEAR(singular(1) / across, 1, 1e-9);
  EXPECT_NEAR(singular(2), 1, 1e-9);
  EXPECT_LE((s.g.col(2) - g0.col(2)).norm(), 1e-9);  // (I + dt R(Omega)) e_z = e_z
  report("eq16_scaling_after_1e5_steps", singular(0));
  report("eq16_orthonormality_after_1e5_steps", orthonormality_error(s.g));
}

// e. Paper, constant torque about a principal axis of a body at rest: Omega grows linearly,
// which the second-order Taylor step of eq. 13 reproduces exactly.
TEST(IntegratorPaper, ConstantTorqueSpinUpIsExact) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3);
  BodyState s;
  s.g = generic_rotation(1.3, Vec3(-2, 1, 0.5));
  const Real torque_magnitude = 2.0;
  const Vec3 torque = s.g.col(2) * torque_magnitude;  // world torque along the body's z axis
  const Real dt = 1e-3;
  const int n = 1000;
  for (int k = 0; k < n; ++k)
    integrate_paper(brick.body, Vec3::Zero(), Vec3::Zero(), torque, dt, s);
  const Vec3 omega_exact(0, 0, torque_magnitude * n * dt / brick.moments.z());
  EXPECT_LE((s.omega - omega_exact).norm(), 1e-12 * omega_exact.norm());
}

// e. Paper, torque-free tumbling: Omega is second order (eq. 13 is a Taylor step with the exact
// first and second derivatives of eqs. 17-18), so its error at a fixed time falls 4x per halving.
TEST(IntegratorPaper, OmegaIsSecondOrder) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3, generic_rotation(0.7, Vec3(1, 2, 3)));
  const Vec3 w0 = Vec3(0.3, -1.1, 0.7).normalized();  // principal axes, |Omega| = 1
  const Real t_end = 10;

  // Reference: RK4 with a step 100x below the smallest tested one.
  Vec3 w_ref = w0;
  const int ref_steps = 200000;
  for (int k = 0; k < ref_steps; ++k) w_ref = rk4_step(brick.moments, w_ref, t_end / ref_steps);

  std::vector<Real> errors;
  for (int n : {500, 1000, 2000}) {
    BodyState s;
    s.omega = brick.from_principal(w0);
    for (int k = 0; k < n; ++k)
      integrate_paper(brick.body, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), t_end / n, s);
    errors.push_back((brick.to_principal(s.omega) - w_ref).norm());
  }
  const Real ratio1 = errors[0] / errors[1], ratio2 = errors[1] / errors[2];
  report("paper_omega_error_dt_0.02", errors[0]);
  report("paper_omega_convergence_ratio_1", ratio1);
  report("paper_omega_convergence_ratio_2", ratio2);
  EXPECT_GT(ratio1, 3.5);
  EXPECT_LT(ratio1, 4.5);
  EXPECT_GT(ratio2, 3.5);
  EXPECT_LT(ratio2, 4.5);
}

// f. Default, constant torque on a tumbling body: the kick adds N dt to the world angular
// momentum and the drift keeps it, so L_n = L_0 + N n dt.
TEST(IntegratorDefault, ConstantTorqueGivesLinearMomentum) {
  const Brick brick = make_brick(3.0, 1.0, 0.6, 0.3, generic_rotation(0.7, Vec3(1, 2, 3)));
  BodyState s;
  s.g = generic_rotation(1.3, Vec3(-2, 1, 0.5));
  s.omega = Vec3(0.3, -1.1, 0.7);
  const Vec3 torque(0.3, -0.2, 0.5);
  const Real dt = 1e-3;
  const int n = 1000;
  const Vec3 l0 = angular_momentum(brick.body, s);
  for (int k = 0; k < n; ++k)
    integrate_default(brick.body, Vec3::Zero(), Vec3::Zero(), torque, dt, s);
  const Vec3 l_exact = l0 + torque * (n * dt);
  EXPECT_LE((angular_momentum(brick.body, s) - l_exact).norm(), 1e-12 * l_exact.norm());
  EXPECT_LT(orthonormality_error(s.g), 1e-12);
}

}  // namespace test_integrators
}  // namespace tem
