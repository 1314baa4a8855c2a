#include "forces/solver_sync.hpp"
#include "forces/overlap_correction.hpp"

#include <algorithm>

#include "forces/system_energies.hpp"

namespace tem {

CorrectionReport correct_overlap(const Model& model, ContactForces& f, Real dt,
                                 Real energy_before, State& state, SolverSync* sync) {
  CorrectionReport report;
  if (f.points.empty() && !sync) return report;
  std::vector<Real>& targets = f.correction.targets;
  targets.assign(f.points.size(), 0);
  std::vector<char>& held = f.correction.held;
  held.assign(f.points.size(), 0);
  bool any = false;
  for (size_t i = 0; i < f.points.size(); ++i) {
    const ContactPoint& c = f.points[i];
    Real size = body_size(model, c.body_a);
    if (c.body_b >= 0) size = std::min(size, body_size(model, c.body_b));
    // The patch's depth at every point: a corner's own depth is not known (an extreme corner is
    // often an edge's crossing with the other surface, at depth 0, beside the deep node).
    const Real excess = f.patch_depth[c.patch] - kOverlapSlop * size;
    if (excess > 0) {
      targets[i] = excess / dt;  // all of it in this step
      any = true;
    } else if (c.depth >= 0) {
      held[i] = 1;  // in contact: the move keeps it so
    }
  }
  if (sync) any = sync->sum(any ? 1 : 0) > 0;
  if (!any) return report;
  // Nothing dissipated (bodies at rest: the contacts only cancelled what gravity added), nothing
  // to fund a lift with: the move would be scaled to nothing. Skipping the solve then is what
  // makes resting piles cheap; it forgoes only moves that lift nothing (purely sideways), which
  // wait for the next step that dissipates.
  const Energies after = system_energies(model, state, sync);
  const Real dissipated = energy_before - after.total();
  if (!(dissipated > 1e-12 * (std::abs(after.kinetic) + std::abs(after.potential)))) return report;

  std::vector<BodyResponse>& still = f.correction.still;
  still = f.responses;
  for (BodyResponse& r : still) r.velocity = r.angular_velocity = Vec3::Zero();
  std::vector<BodyResponse>& moved = f.correction.moved;
  SolverSettings stopping;
  stopping.tolerance = model.scene.contact.tolerance;
  stopping.max_sweeps = model.scene.contact.max_sweeps;
  stopping.colour_sweeps = model.scene.contact.colour_sweeps;
  stopping.sync = sync;
  stopping.held = &held;
  // By the step's own solver (force_model.hpp).
  f.correction.patches = f.friction;
  force_model(model.scene.contact).separate(targets, stopping, f);

  // The potential energy the move costs, against what the step dissipated.
  Real lift = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (!sync || sync->owns(static_cast<int>(b)))
      lift -= model.bodies[b].inertia.mass * model.scene.gravity.dot(dt * moved[b].velocity);
  if (sync) lift = sync->sum(lift);
  report.scale = lift > 0 ? std::clamp<Real>(dissipated / lift, 0, 1) : 1;
  if (report.scale == 0) return report;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].driven() || (sync && !sync->owns(static_cast<int>(b)))) continue;
    BodyState& s = state.bodies[b];
    s.x += report.scale * dt * moved[b].velocity;
    s.g = cayley(report.scale * dt * moved[b].angular_velocity) * s.g;
  }
  report.applied = true;
  return report;
}

}  // namespace tem
