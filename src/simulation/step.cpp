#include "simulation/step.hpp"

#include <chrono>
#include <cmath>

#include "dynamics/integrator.hpp"
#include "contact/contact_margins.hpp"
#include "contact/refreshed_patches.hpp"
#include "forces/overlap_correction.hpp"
#include "process/motion.hpp"
#include "process/sensors.hpp"
#include "simulation/substep_count.hpp"
#include "support/parallel.hpp"

namespace tem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point& start) {
  const Clock::time_point now = Clock::now();
  const double s = std::chrono::duration<double>(now - start).count();
  start = now;
  return s;
}

// The work of the external loads over a step from `before` to `after`: F.(x1 - x0) and
// N.(dt omega1) (the default integrator's drift turns a body by its spin after the kick).
Real external_work(const Model& model, const ExternalLoads& loads,
                   const std::vector<BodyState>& before, const std::vector<BodyState>& after,
                   Real dt) {
  Real work = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].driven()) continue;
    work += loads.force[b].dot(after[b].x - before[b].x);
    work += loads.torque[b].dot(dt * after[b].angular_velocity_world());
  }
  return work;
}

// The work the bodies with a prescribed motion do on the others over the step through
// contact: minus the contact force and torque on each, times its velocities of the step.
Real driven_work(const Model& model, const State& state, const ContactForces& forces, Real dt) {
  Real work = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (!model.bodies[b].motion || model.bodies[b].fixed) continue;
    const BodyState& s = state.bodies[b];
    work -= forces.force[b].dot(s.v) + forces.torque[b].dot(s.angular_velocity_world());
  }
  work *= dt;
  // Sliding surfaces (conveyor belts): the friction impulse j on B (-j on A) against the
  // surfaces' relative slide does -j.(s_B - s_A) on the others.
  for (const PatchFriction& p : forces.friction)
    work -= p.t1 * p.surface_slip.x() + p.t2 * p.surface_slip.y();
  return work;
}

// One sub-step (the whole step without contact.substeps) of length h from `state`, with the
// forces of the last solve in w.forces: stages 5 (integration), 6 (overlap correction, after the
// last sub-step only), the clock and the driven bodies, 7 (sensors). `budget`, where the step
// corrects overlap, is the energy the step started from plus the work the driven bodies and the
// external loads have done in it so far. Returns whether the correction moved bodies.
bool integrate_substep(const Model& model, State& state, Workspace& w, Real h, bool last,
                       Real step_start_time, int substep, Real* budget) {
  const SceneDef& scene = model.scene;
  const bool loaded = !w.loads.empty();
  const bool sensing = !scene.sensors.empty();
  if (!w.contact.reach.empty() || loaded || sensing) w.before = state.bodies;
  // Prescribed motion (process/motion.hpp): its work on the others is no dissipation either.
  const Real pushed = model.any_motion && !w.forces.force.empty()
                          ? driven_work(model, state, w.forces, h)
                          : 0;
  state.driven_work += pushed;
  if (budget) *budget += pushed;
  // 5. Integration of every moving body under gravity and its contact force and torque.
  const bool all = w.subset.empty();
  parallel_for(static_cast<long long>(model.bodies.size()), 256, [&](long long i) {
    if (model.bodies[i].driven() || (!all && !w.subset.owned[i]) || w.sleep.is_frozen(i)) return;
    const Vec3 force = loaded ? Vec3(w.forces.force[i] + w.loads.force[i]) : w.forces.force[i];
    const Vec3 torque = loaded ? Vec3(w.forces.torque[i] + w.loads.torque[i]) : w.forces.torque[i];
    integrate(scene.integrator, model.bodies[i].inertia, scene.gravity, force, torque, h,
              state.bodies[i]);
  });
  // 6. Correction of existing overlap, within the energy the contacts dissipated over the step
  // (default). The external loads' work is no dissipation of the contacts': a drag's loss must
  // not fund a correction, nor a push's gain hide one. With sub-steps it runs once, after the
  // last: each sub-step's speculative contacts already keep gaps from closing, and what overlap
  // the step leaves is what the correction is for; a correction after every sub-step solved the
  // separation n times for one step's result.
  if (budget && loaded) *budget += external_work(model, w.loads, w.before, state.bodies, h);
  const bool corrected =
      budget && last && correct_overlap(model, w.forces, h, *budget, state, w.sync).applied;
  if (last) {
    ++state.step;
    // No drift from summing dt; and where dt divides a second (1e-5, 1/240), step / steps per
    // second, the double nearest the decimal time (15000 * 1e-5 is 0.15000000000000002).
    const Real per_second = std::round(1 / scene.time_step);
    state.time = std::abs(per_second * scene.time_step - 1) < 1e-12
                     ? static_cast<Real>(state.step) / per_second
                     : static_cast<Real>(state.step) * scene.time_step;
  } else {
    state.time = step_start_time + (substep + 1) * h;
  }
  // Bodies with a prescribed motion go where it puts them at the new time, with the velocities
  // of the step's next sub-step (after its last, of the next step's fewest: find_contact_forces
  // gives them those of its own count).
  if (model.any_motion) move_driven_bodies(model, state, last ? substep_time(scene) : h);
  // 7. Sensors: plane crossings and the contact forces on the bodies they watch.
  if (sensing) accumulate_sensors(model, w.before, state, w.forces);
  return corrected;
}

}  // namespace

void step(const Model& model, State& state, Workspace& w) {
  find_contact_forces(model, state, w);
  advance(model, state, w);
}

void find_contact_forces(const Model& model, State& state, Workspace& w) {
  const SceneDef& scene = model.scene;
  Clock::time_point clock = Clock::now();
  w.substeps = scene.contact.substeps;
  // Bodies with a prescribed motion hold the velocities of the fewest sub-steps until this step's
  // count is chosen (below), so that the count, and a second call at the same state, find them so.
  const bool counted = model.any_motion && scene.contact.max_substeps > 0;
  if (counted) move_driven_bodies(model, state, substep_time(scene));
  // A scene wholly asleep has no contact to find (simulation/sleep.hpp).
  if (scene.sleep && everything_sleeps(model, state, w.loads, w.sleep, w.patches, w.forces)) return;

  // 1. Broad phase: block pairs and block-wall pairs whose world bounds overlap, grown by each
  // body's reach where contact is made before overlap.
  const ExternalLoads* loads = w.loads.empty() ? nullptr : &w.loads;
  contact_reaches(model, state, w.contact.reach, loads, &w.subset);
  w.contact.broad_phase.update(model, state, w.contact.reach, &w.subset);
  if (scene.sleep) leave_sleepers_out(model, state, w.loads, w.sleep, w.contact.broad_phase);
  w.times.broad_phase += seconds_since(clock);

  // 2-3. Narrow phase and patches: node in element, edge through face, grouping; a pair that
  // has barely moved takes last step's features (pair_cache.hpp; one process only: the ranks'
  // checkpoints do not hold them).
  w.contact.use_features = scene.contact.pair_cache && w.subset.empty();
  if (!w.contact.use_features) {
    w.contact.features.clear();
    w.contact.separations.clear();
  }
  find_patches(model, patch_variant(scene), w.contact, w.patches);
  // How many sub-steps this step takes, from how fast its contacts close and turn.
  w.substeps = substeps_for_step(model, state, w.patches);
  // A step of more sub-steps gives them the chord of its own sub-step: the mean velocity over a
  // longer one is off by their acceleration times half the difference (a shaker's at its turn).
  if (counted && w.substeps != scene.contact.substeps)
    move_driven_bodies(model, state, scene.time_step / w.substeps);
  w.times.narrow_phase += seconds_since(clock);
  w.times.block_pairs += w.contact.pairs_tested;
  w.times.cached_pairs += w.contact.pairs_cached;
  w.times.apart_pairs += w.contact.pairs_apart;

  // 4. Forces: the contact impulses of the scene's force model, as forces held over the step
  // (with sub-steps, over its first sub-step).
  compute_contact_forces(model, state, w.patches, scene.time_step / w.substeps, w.forces, loads,
                         w.sync);
  w.times.forces += seconds_since(clock);
}

void advance(const Model& model, State& state, Workspace& w) {
  const SceneDef& scene = model.scene;
  Clock::time_point clock = Clock::now();
  const int substeps = w.substeps;
  const Real h = scene.time_step / substeps;
  const Real step_start_time = state.time;
  // Sub-steps (refreshed_patches.hpp): the bodies where the step's detection saw them (for the
  // reach check); the first sub-step's forces are already found.
  if (substeps > 1) w.detected = state.bodies;
  const ExternalLoads* loads = w.loads.empty() ? nullptr : &w.loads;
  bool corrected = false, unconverged = false, scaled = false;
  int sweeps = 0;
  // The overlap correction's budget (integrate_substep): the energy the step starts from.
  bool correct = force_model(scene.contact).corrects_overlap() &&
                 scene.integrator == IntegratorKind::default_ && !w.patches.empty();
  if (w.sync) correct = w.sync->sum(correct ? 1 : 0) > 0;  // all ranks, or none
  Real budget = correct ? system_energies(model, state, w.sync).total() : 0;
  for (int s = 0; s < substeps; ++s) {
    if (s > 0) {
      w.times.integrate += seconds_since(clock);
      // 3'. The detected pairs' patches again at the sub-step's poses, from their features.
      refresh_patches(model, state, w.contact, w.patches, w.refreshed, w.substep_patches);
      w.times.narrow_phase += seconds_since(clock);
      // 4'. The sub-step's forces.
      compute_contact_forces(model, state, w.substep_patches, h, w.forces, loads, w.sync);
      w.times.forces += seconds_since(clock);
    }
    sweeps += w.forces.solver.sweeps;
    unconverged = unconverged || !w.forces.solver.converged;
    scaled = scaled || w.forces.solver.scale < 1;
    w.times.fallback_islands += w.forces.solver.fallback_islands;
    w.times.regularised_islands += w.forces.solver.regularised_islands;
    corrected = integrate_substep(model, state, w, h, s + 1 == substeps, step_start_time, s,
                                  correct ? &budget : nullptr) ||
                corrected;
  }
  if (corrected) ++w.times.corrected_steps;
  // Bodies that moved farther than their reach could meet a contact already overlapping.
  if (!w.contact.reach.empty())
    w.times.outran_margin += bodies_outrunning_reach(model, w.contact.reach,
                                                     substeps > 1 ? w.detected : w.before,
                                                     state.bodies);
  // Rest timers and islands falling asleep, with the velocities the step left (sleep.hpp).
  if (scene.sleep) update_sleep(model, w.patches, w.loads, step_start_time, w.sleep, state);
  w.times.integrate += seconds_since(clock);

  ++w.times.steps;
  w.times.substeps += substeps;
  w.times.max_substeps = std::max(w.times.max_substeps, substeps);
  w.times.patches += static_cast<long long>(w.patches.size());
  w.times.points += static_cast<long long>(w.forces.points.size());
  w.times.sweeps += sweeps;
  w.times.max_sweeps = std::max(w.times.max_sweeps, sweeps);
  if (static_cast<int>(w.times.steps_by_sweeps.size()) <= sweeps)
    w.times.steps_by_sweeps.resize(static_cast<size_t>(sweeps) + 1, 0);
  ++w.times.steps_by_sweeps[static_cast<size_t>(sweeps)];
  if (unconverged) ++w.times.unconverged_steps;
  if (scaled) ++w.times.scaled_steps;
}

int first_non_finite_body(const State& state) {
  for (size_t i = 0; i < state.bodies.size(); ++i) {
    const BodyState& s = state.bodies[i];
    if (!s.x.allFinite() || !s.v.allFinite() || !s.g.allFinite() || !s.omega.allFinite())
      return static_cast<int>(i);
  }
  return -1;
}

}  // namespace tem
