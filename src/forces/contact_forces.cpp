#include "forces/solver_sync.hpp"
#include "forces/contact_forces.hpp"

#include <algorithm>

#include "forces/materials.hpp"
#include "forces/warm_start.hpp"
#include "support/parallel.hpp"

namespace tem {
namespace {

Vec3 start_spin(const Model& model, const State& state, int body) {
  if (body < 0 || model.bodies[body].fixed) return Vec3::Zero();
  return state.bodies[body].angular_velocity_world();
}

// What restitution answers and what keeps the impulses from adding energy (semm.cpp): the
// normal relative velocity (B minus A) at each point, and each patch's slip and spin at its
// centre, with the velocities at the start of the step; and each patch's coefficients from its
// materials (materials.hpp). Each point and each patch on its own, shared among the threads
// (with sub-steps this runs every sub-step, and on one thread it was a sixth of the forces).
void start_velocities(const Model& model, const State& state,
                      const std::vector<ContactPatch>& patches, ContactForces& f) {
  f.approach.resize(f.points.size());
  f.approach_linear.resize(f.points.size());
  auto centre_velocity = [&](int body) {
    return body < 0 || model.bodies[body].fixed ? Vec3::Zero() : state.bodies[body].v;
  };
  parallel_for(static_cast<long long>(f.points.size()), 256, [&](long long i) {
    const ContactPoint& c = f.points[i];
    f.approach_linear[i] = c.normal.dot(centre_velocity(c.body_b) - centre_velocity(c.body_a));
    f.approach[i] = c.normal.dot(material_point_velocity(model, state, c.body_b, c.point) -
                                 material_point_velocity(model, state, c.body_a, c.point));
  });
  // Each patch's run of points (patch_points lays them out patch by patch); a patch without
  // points keeps an empty run.
  f.friction.assign(patches.size(), PatchFriction{});
  for (size_t i = 0; i < f.points.size();) {
    const int patch = f.points[i].patch;
    f.friction[patch].first = static_cast<int>(i);
    while (i < f.points.size() && f.points[i].patch == patch) ++i;
    f.friction[patch].last = static_cast<int>(i);
  }
  parallel_for(static_cast<long long>(patches.size()), 64, [&](long long patch) {
    PatchFriction& p = f.friction[patch];
    if (p.last == p.first) return;
    const ContactPoint& c = f.points[p.first];
    p.body_a = c.body_a;
    p.body_b = c.body_b;
    p.wall = c.wall;
    p.centre = patches[c.patch].point;
    p.normal = c.normal;
    p.tangent1 = c.tangent1;
    p.tangent2 = c.tangent2;
    // A belt's sliding surface (motion.surface_velocity) slides past the patch: it adds to the
    // slip that friction answers, not to the approach (its normal part is the belt's to keep
    // out: only its tangential part acts).
    const Vec3 surface = surface_velocity(model, c.body_b, state.time) -
                         surface_velocity(model, c.body_a, state.time);
    p.surface_slip = Vec3(p.tangent1.dot(surface), p.tangent2.dot(surface), 0);
    const Vec3 dv = material_point_velocity(model, state, c.body_b, p.centre) -
                    material_point_velocity(model, state, c.body_a, p.centre);
    const Vec3 dw = start_spin(model, state, c.body_b) - start_spin(model, state, c.body_a);
    p.start_slip = Vec3(p.tangent1.dot(dv), p.tangent2.dot(dv), p.normal.dot(dw)) + p.surface_slip;
    const PairCoefficients& k = contact_coefficients(model, c.body_a, c.body_b, c.wall);
    p.friction = k.friction;
    p.restitution = k.restitution;
    p.rolling_resistance = k.rolling_resistance;
    if (k.rolling_resistance > 0) {
      p.rolling_radius = rolling_radius(model, state, c.body_a, c.body_b, p.centre);
      p.start_roll1 = p.tangent1.dot(dw);
      p.start_roll2 = p.tangent2.dot(dw);
    }
  });
}

// 1% of each body's size: the distance below which a contact point is the same from one step
// to the next.
void match_radii(const Model& model, std::vector<Real>& radius) {
  radius.resize(model.bodies.size());
  for (size_t b = 0; b < model.bodies.size(); ++b)
    radius[b] = 0.01 * body_size(model, static_cast<int>(b));
}

}  // namespace

void compute_contact_forces(const Model& model, const State& state,
                            const std::vector<ContactPatch>& patches, Real dt, ContactForces& f,
                            const ExternalLoads* loads, SolverSync* sync) {
  const SceneDef& scene = model.scene;
  const size_t n_bodies = model.bodies.size();
  f.force.assign(n_bodies, Vec3::Zero());
  f.torque.assign(n_bodies, Vec3::Zero());
  f.patch_forces.assign(patches.size(), PatchForce{});
  f.patch_depth.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k) f.patch_depth[k] = patches[k].depth;
  std::swap(f.previous_points, f.points);
  std::swap(f.previous_impulses, f.impulses);
  std::swap(f.previous_friction, f.friction);
  f.points.clear();
  f.impulses.clear();
  f.solver = SolverReport{};
  f.centres.resize(n_bodies);
  for (size_t b = 0; b < n_bodies; ++b) f.centres[b] = state.bodies[b].x;
  if (scene.contact.model == ContactModel::penalty) {
    f.solver.sweeps = 0;
    for (size_t i = 0; i < patches.size(); ++i)
      patch_points(patches[i], static_cast<int>(i), scene.contact.points == PatchPoints::one,
                   f.points);
    penalty_forces(model, state, patches, f.points, f.centres, f.springs, f.force, f.torque,
                   f.normal_magnitude, f.tangential_magnitude);
    for (size_t k = 0; k < patches.size(); ++k)
      f.patch_forces[k] = {f.normal_magnitude[k], f.tangential_magnitude[k]};
    return;
  }
  if (patches.empty() && !sync) return;

  const bool paper = scene.contact.model == ContactModel::semm_paper;
  const bool one_point = scene.contact.points == PatchPoints::one;
  for (size_t i = 0; i < patches.size(); ++i)
    patch_points(patches[i], static_cast<int>(i), one_point, f.points);
  body_responses(model, state, dt, f.responses, loads);

  if (paper) {
    f.solver = solve_semm_paper(f.points, f.responses, f.centres, f.impulses);
  } else {
    start_velocities(model, state, patches, f);
    SolverSettings settings;
    settings.friction = scene.contact.friction;
    settings.restitution = scene.contact.restitution;
    settings.per_patch = true;  // each patch's coefficients from its materials
    settings.tolerance = scene.contact.tolerance;
    settings.max_sweeps = scene.contact.max_sweeps;
    settings.colour_sweeps = scene.contact.colour_sweeps;
    settings.time_step = dt;
    settings.sync = sync;
    settings.conjugate_gradients = scene.contact.conjugate_gradients;
    // Slower than what gravity adds in two steps is resting contact, not an impact.
    settings.restitution_threshold = 2 * scene.gravity.norm() * dt;
    if (f.match_radius.size() != n_bodies) match_radii(model, f.match_radius);
    warm_start(f.previous_points, f.previous_impulses, f.points, f.match_radius, f.impulses);
    warm_start_friction(f.previous_friction, f.match_radius, f.friction);
    if (scene.contact.solver == ContactSolver::rows) {
      normal_targets(f.points, f.approach, f.approach_linear, settings, f.targets, &f.friction);
      f.solver = solve_semm_rows(f.points, f.approach, f.targets, f.responses, f.centres, settings,
                                 f.friction, f.impulses, f.rows);
    } else if (scene.contact.solver == ContactSolver::newton) {
      normal_targets(f.points, f.approach, f.approach_linear, settings, f.targets, &f.friction);
      f.solver = solve_semm_newton(f.points, f.approach, f.targets, f.responses, f.centres,
                                   settings, f.friction, f.impulses, f.newton);
    } else {
      f.solver = solve_semm(f.points, f.approach, f.responses, f.centres, settings, f.friction,
                            f.impulses);
    }
  }

  // Impulses to forces held through the step: on B +j, on A -j, with their moments.
  auto push = [&](int body_a, int body_b, const Vec3& at, const Vec3& on_b, const Vec3& moment) {
    add_contact_force(f.centres, body_a, body_b, at, on_b, moment, f.force, f.torque);
  };
  for (size_t i = 0; i < f.points.size(); ++i) {
    const ContactPoint& c = f.points[i];
    const Vec3 on_b = f.impulses[i].normal / dt * c.normal;
    push(c.body_a, c.body_b, c.point, on_b, Vec3::Zero());
    f.patch_forces[c.patch].normal += f.impulses[i].normal / dt;
  }
  if (!paper) {
    for (size_t k = 0; k < f.friction.size(); ++k) {
      const PatchFriction& p = f.friction[k];
      const Vec3 on_b = (p.t1 * p.tangent1 + p.t2 * p.tangent2) / dt;
      Vec3 moment = p.twist / dt * p.normal;
      if (p.roll1 != 0 || p.roll2 != 0)  // rolling resistance
        moment += (p.roll1 * p.tangent1 + p.roll2 * p.tangent2) / dt;
      push(p.body_a, p.body_b, p.centre, on_b, moment);
      f.patch_forces[k].tangential = on_b.norm();
    }
  }
}

}  // namespace tem
