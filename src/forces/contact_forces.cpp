#include "forces/contact_forces.hpp"

#include <algorithm>

#include "forces/warm_start.hpp"

namespace tem {
namespace {

// Relative velocity (B minus A) at each point with the velocities at the start of the step, in
// the point's frame (normal, tangent1, tangent2): what restitution answers, and what keeps the
// impulses from adding energy (semm.hpp).
void approach_velocities(const Model& model, const State& state, ContactForces& f) {
  f.approach.resize(f.points.size());
  auto velocity = [&](int body, const Vec3& p) -> Vec3 {
    if (body < 0 || model.bodies[body].fixed) return Vec3::Zero();
    const BodyState& s = state.bodies[body];
    return s.v + s.angular_velocity_world().cross(p - s.x);
  };
  for (size_t i = 0; i < f.points.size(); ++i) {
    const ContactPoint& c = f.points[i];
    const Vec3 u = velocity(c.body_b, c.point) - velocity(c.body_a, c.point);
    f.approach[i] = Vec3(c.normal.dot(u), c.tangent1.dot(u), c.tangent2.dot(u));
  }
}

// 1% of each body's size: the distance below which a contact point is the same from one step
// to the next.
void match_radii(const Model& model, std::vector<Real>& radius) {
  radius.assign(model.bodies.size(), 0);
  for (size_t b = 0; b < model.bodies.size(); ++b)
    for (const BlockInstance& i : model.bodies[b].blocks)
      radius[b] = std::max(radius[b],
                           0.01 * (i.offset.norm() + model.blocks[i.block].bounding_radius()));
}

}  // namespace

void compute_contact_forces(const Model& model, const State& state,
                            const std::vector<ContactPatch>& patches, ContactForces& f) {
  const SceneDef& scene = model.scene;
  const Real dt = scene.time_step;
  const size_t n_bodies = model.bodies.size();
  f.force.assign(n_bodies, Vec3::Zero());
  f.torque.assign(n_bodies, Vec3::Zero());
  f.patch_forces.assign(patches.size(), PatchForce{});
  std::swap(f.previous_points, f.points);
  std::swap(f.previous_impulses, f.impulses);
  f.points.clear();
  f.impulses.clear();
  f.solver = SolverReport{};
  if (patches.empty()) return;

  const bool paper = scene.contact.model == ContactModel::semm_paper;
  const bool one_point = scene.contact.points == PatchPoints::one;
  for (size_t i = 0; i < patches.size(); ++i)
    patch_points(patches[i], static_cast<int>(i), one_point, f.points);
  body_responses(model, state, dt, f.responses);
  f.centres.resize(n_bodies);
  for (size_t b = 0; b < n_bodies; ++b) f.centres[b] = state.bodies[b].x;

  if (paper) {
    f.solver = solve_semm_paper(f.points, f.responses, f.centres, f.impulses);
  } else {
    approach_velocities(model, state, f);
    SolverSettings settings;
    settings.friction = scene.contact.friction;
    settings.restitution = scene.contact.restitution;
    // Slower than what gravity adds in two steps is resting contact, not an impact.
    settings.restitution_threshold = 2 * scene.gravity.norm() * dt;
    if (f.match_radius.size() != n_bodies) match_radii(model, f.match_radius);
    warm_start(f.previous_points, f.previous_impulses, f.points, f.match_radius, f.impulses);
    f.solver = solve_semm(f.points, f.approach, f.responses, f.centres, settings, f.impulses);
  }

  // Impulses to forces held through the step: on B +j, on A -j, with their moments.
  std::vector<Vec3> tangential(patches.size(), Vec3::Zero());
  for (size_t i = 0; i < f.points.size(); ++i) {
    const ContactPoint& c = f.points[i];
    const PointImpulse& p = f.impulses[i];
    const Vec3 t = (p.t1 * c.tangent1 + p.t2 * c.tangent2) / dt;
    const Vec3 on_b = p.normal / dt * c.normal + t;
    if (!model.bodies[c.body_a].fixed) {
      f.force[c.body_a] -= on_b;
      f.torque[c.body_a] -= (c.point - f.centres[c.body_a]).cross(on_b);
    }
    if (c.body_b >= 0 && !model.bodies[c.body_b].fixed) {
      f.force[c.body_b] += on_b;
      f.torque[c.body_b] += (c.point - f.centres[c.body_b]).cross(on_b);
    }
    f.patch_forces[c.patch].normal += p.normal / dt;
    tangential[c.patch] -= t;  // on A
  }
  for (size_t k = 0; k < patches.size(); ++k) f.patch_forces[k].tangential = tangential[k].norm();
}

}  // namespace tem
