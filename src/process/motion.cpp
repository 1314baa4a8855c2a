#include "process/motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tem {
namespace {

// Time spent moving by t: 0 before start, t - start inside the window, end - start after.
Real moving_time(const MotionDef& m, Real t) { return std::clamp<Real>(t, m.start, m.end) - m.start; }

Mat3 turned(const Vec3& omega, Real tau) {
  const Real rate = omega.norm();
  if (rate == 0 || tau == 0) return Mat3::Identity();
  return Eigen::AngleAxis<Real>(rate * tau, omega / rate).toRotationMatrix();
}

}  // namespace

DrivenPose motion_pose(const Body& body, Real t) {
  const MotionDef& m = *body.motion;
  const Mat3 g0 = body.start_rotation;
  const Vec3 x0 = body.start_position - g0 * body.origin_offset;
  const Real tau = moving_time(m, t);
  const Vec3 center = m.center.value_or(x0);
  const Mat3 r = turned(m.angular_velocity, tau);
  Vec3 x = center + r * (x0 - center) + m.velocity * tau;
  if (m.oscillation)
    x += m.oscillation->amplitude *
         std::sin(2 * std::numbers::pi * m.oscillation->frequency * tau);
  return {x, r * g0};
}

void move_driven_bodies(const Model& model, State& state, Real h) {
  const Real t = state.time;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    if (!body.motion || body.fixed) continue;
    const DrivenPose now = motion_pose(body, t), next = motion_pose(body, t + h);
    BodyState& s = state.bodies[b];
    s.x = now.x;
    s.g = now.g;
    s.v = (next.x - now.x) / h;
    const Real turning = moving_time(*body.motion, t + h) - moving_time(*body.motion, t);
    s.omega = now.g.transpose() * (body.motion->angular_velocity * (turning / h));
  }
}

bool has_motion(const Model& model) {
  return std::any_of(model.bodies.begin(), model.bodies.end(),
                     [](const Body& b) { return b.motion.has_value(); });
}

}  // namespace tem
