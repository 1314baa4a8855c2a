#include "forces/semm_step.hpp"

#include <stdexcept>

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

// A patch's friction and its points in a record: every field but the keys and the indices
// (first, last, patch), which the order of the records gives.
constexpr size_t kFrictionNumbers = 29, kPointNumbers = 14;

void write_friction(RecordWriter& w, const PatchFriction& p) {
  for (const Vec3& v : {p.centre, p.normal, p.tangent1, p.tangent2, p.start_slip}) w.put(v);
  for (const Real x : {p.t1, p.t2, p.twist, p.roll1, p.roll2, p.start_roll1, p.start_roll2,
                       p.friction, p.restitution, p.rolling_resistance, p.rolling_radius})
    w.put(x);
  w.put(p.surface_slip);
}

PatchFriction read_friction(RecordReader& r) {
  PatchFriction p;
  for (Vec3* v : {&p.centre, &p.normal, &p.tangent1, &p.tangent2, &p.start_slip}) *v = r.vec3();
  for (Real* x : {&p.t1, &p.t2, &p.twist, &p.roll1, &p.roll2, &p.start_roll1, &p.start_roll2,
                  &p.friction, &p.restitution, &p.rolling_resistance, &p.rolling_radius})
    *x = r.number();
  p.surface_slip = r.vec3();
  return p;
}

}  // namespace

bool begin_semm_step(const ForceStep& step, ContactForces& f) {
  std::swap(f.previous_points, f.points);
  std::swap(f.previous_impulses, f.impulses);
  std::swap(f.previous_friction, f.friction);
  f.points.clear();
  f.impulses.clear();
  if (step.patches.empty() && !step.sync) {
    f.friction.clear();  // no contact this step: no memory for the next
    return false;
  }
  const bool one_point = step.model.scene.contact.points == PatchPoints::one;
  for (size_t i = 0; i < step.patches.size(); ++i)
    patch_points(step.patches[i], static_cast<int>(i), one_point, f.points);
  body_responses(step.model, step.state, step.dt, f.responses, step.loads);
  return true;
}

SolverSettings begin_default_semm(const ForceStep& step, ContactForces& f) {
  const SceneDef& scene = step.model.scene;
  start_velocities(step.model, step.state, step.patches, f);
  SolverSettings settings;
  settings.friction = scene.contact.friction;
  settings.restitution = scene.contact.restitution;
  settings.per_patch = true;  // each patch's coefficients from its materials
  settings.tolerance = scene.contact.tolerance;
  settings.max_sweeps = scene.contact.max_sweeps;
  settings.colour_sweeps = scene.contact.colour_sweeps;
  settings.time_step = step.dt;
  settings.sync = step.sync;
  settings.conjugate_gradients = scene.contact.conjugate_gradients;
  // Slower than what gravity adds in two steps is resting contact, not an impact.
  settings.restitution_threshold = 2 * scene.gravity.norm() * step.dt;
  if (f.match_radius.size() != step.model.bodies.size()) match_radii(step.model, f.match_radius);
  warm_start(f.previous_points, f.previous_impulses, f.points, f.match_radius, f.impulses);
  warm_start_friction(f.previous_friction, f.match_radius, f.friction);
  return settings;
}

void DefaultSemmModel::separate(const std::vector<Real>& targets, const SolverSettings& stopping,
                                ContactForces& f) const {
  solve_separation(f.points, targets, f.correction.still, f.centres, f.correction.patches,
                   f.correction.impulses, f.correction.moved, stopping, &f.rows);
}

void semm_impulses_to_forces(Real dt, bool friction, ContactForces& f) {
  auto push = [&](int body_a, int body_b, const Vec3& at, const Vec3& on_b, const Vec3& moment) {
    add_contact_force(f.centres, body_a, body_b, at, on_b, moment, f.force, f.torque);
  };
  for (size_t i = 0; i < f.points.size(); ++i) {
    const ContactPoint& c = f.points[i];
    const Vec3 on_b = f.impulses[i].normal / dt * c.normal;
    push(c.body_a, c.body_b, c.point, on_b, Vec3::Zero());
    f.patch_forces[c.patch].normal += f.impulses[i].normal / dt;
  }
  if (!friction) return;
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

void save_semm_memory(const ContactForces& f, std::vector<MemoryRecord>& out) {
  for (size_t i = 0; i < f.points.size();) {
    const int k = f.points[i].patch;
    MemoryRecord record;
    record.body_a = f.points[i].body_a;
    record.body_b = f.points[i].body_b;
    record.wall = f.points[i].wall;
    RecordWriter w(record.values);
    const bool known = k >= 0 && static_cast<size_t>(k) < f.friction.size();
    write_friction(w, known ? f.friction[k] : PatchFriction{});
    size_t end = i;
    while (end < f.points.size() && f.points[end].patch == k) ++end;
    w.put(static_cast<int>(end - i));
    for (; i < end; ++i) {
      const ContactPoint& c = f.points[i];
      for (const Vec3& v : {c.point, c.normal, c.tangent1, c.tangent2}) w.put(v);
      w.put(c.depth);
      w.put(i < f.impulses.size() ? f.impulses[i].normal : 0.0);
    }
    out.push_back(std::move(record));
  }
}

void load_semm_memory(const std::vector<MemoryRecord>& records, ContactForces& f) {
  f.points.clear();
  f.impulses.clear();
  f.friction.clear();
  f.match_radius.clear();  // per body: rebuilt for the bodies there are now
  for (const MemoryRecord& record : records) {
    RecordReader r(record.values);
    if (!r.has(kFrictionNumbers + 1))
      throw std::runtime_error("a SEMM contact memory record is too short");
    PatchFriction p = read_friction(r);
    const int k = static_cast<int>(f.friction.size());
    p.body_a = record.body_a;
    p.body_b = record.body_b;
    p.wall = record.wall;
    const int count = r.integer();
    if (count < 1 || !r.has(static_cast<size_t>(count) * kPointNumbers))
      throw std::runtime_error("a SEMM contact memory record does not hold its points");
    p.first = static_cast<int>(f.points.size());
    for (int j = 0; j < count; ++j) {
      ContactPoint c;
      c.patch = k;
      c.body_a = record.body_a;
      c.body_b = record.body_b;
      c.wall = record.wall;
      for (Vec3* v : {&c.point, &c.normal, &c.tangent1, &c.tangent2}) *v = r.vec3();
      c.depth = r.number();
      f.points.push_back(c);
      f.impulses.push_back(PointImpulse{r.number()});
    }
    if (!r.done()) throw std::runtime_error("a SEMM contact memory record is too long");
    p.last = static_cast<int>(f.points.size());
    f.friction.push_back(p);
  }
}

}  // namespace tem
