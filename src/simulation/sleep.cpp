#include "simulation/sleep.hpp"

#include <algorithm>
#include <limits>

namespace tem {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Wakes every sleeping body whose island is in `islands` (sorted), restarting its rest timer:
// its support changed, so it must show it rests again before it may sleep.
void wake_islands(const std::vector<long long>& islands, State& state) {
  if (islands.empty()) return;
  for (BodyState& s : state.bodies) {
    if (!s.asleep || !std::binary_search(islands.begin(), islands.end(), s.island)) continue;
    s.asleep = false;
    s.island = -1;
    s.rest_time = 0;
  }
}

void sort_unique(std::vector<long long>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

void refresh_sizes(const Model& model, SleepWorkspace& sleep) {
  if (sleep.size_version == model.population_version && sleep.size.size() == model.bodies.size())
    return;
  sleep.size.resize(model.bodies.size());
  for (size_t b = 0; b < model.bodies.size(); ++b)
    sleep.size[b] = body_size(model, static_cast<int>(b));
  sleep.size_version = model.population_version;
}

bool loaded(const ExternalLoads& loads, size_t b) {
  return !loads.empty() && (!loads.force[b].isZero(0) || !loads.torque[b].isZero(0));
}

}  // namespace

bool everything_sleeps(const Model& model, const State& state, const ExternalLoads& loads,
                       SleepWorkspace& sleep, std::vector<ContactPatch>& patches,
                       ContactForces& forces) {
  if (model.any_motion || !loads.empty()) return false;
  const size_t n = model.bodies.size();
  for (size_t b = 0; b < n; ++b) {
    const BodyState& s = state.bodies[b];
    if (model.bodies[b].fixed) continue;
    if (!s.asleep || !s.v.isZero(0) || !s.omega.isZero(0)) return false;
  }
  sleep.frozen.assign(n, 0);
  for (size_t b = 0; b < n; ++b) sleep.frozen[b] = !model.bodies[b].fixed;
  patches.clear();
  compute_contact_forces(model, state, patches, substep_time(model.scene), forces);
  return true;
}

void leave_sleepers_out(const Model& model, const State& state, const ExternalLoads& loads,
                        SleepWorkspace& sleep, BroadPhase& broad_phase) {
  const size_t n = model.bodies.size();
  sleep.frozen.assign(n, 0);
  // Nobody asleep (a pile still settling): nothing to wake, no pair to drop.
  bool any_asleep = false;
  for (size_t b = 0; b < n && !any_asleep; ++b) any_asleep = state.bodies[b].asleep;
  if (!any_asleep) return;
  // Who wakes: islands touched (in the broad phase's sense) by a body that moves by itself,
  // and islands with a load or a velocity given from outside. Decided from the state's flags
  // alone: a body woken here wakes no one else this step (it may next step, once it moves).
  sleep.wake.clear();
  for (size_t b = 0; b < n; ++b) {
    const BodyState& s = state.bodies[b];
    if (s.asleep && (loaded(loads, b) || !s.v.isZero(0) || !s.omega.isZero(0)))
      sleep.wake.push_back(s.island);
  }
  auto wakes_others = [&](int b) {
    return !model.bodies[b].fixed && !state.bodies[b].asleep;  // free and awake, or driven
  };
  const std::vector<BlockProxy>& proxies = broad_phase.proxies();
  for (const BlockPair& p : broad_phase.block_pairs()) {
    const int a = proxies[p.a].body, b = proxies[p.b].body;
    if (state.bodies[a].asleep && wakes_others(b)) sleep.wake.push_back(state.bodies[a].island);
    if (state.bodies[b].asleep && wakes_others(a)) sleep.wake.push_back(state.bodies[b].island);
  }
  sort_unique(sleep.wake);

  sleep.moving.assign(n, 0);
  for (size_t b = 0; b < n; ++b) {
    const BodyState& s = state.bodies[b];
    sleep.frozen[b] =
        s.asleep && !std::binary_search(sleep.wake.begin(), sleep.wake.end(), s.island);
    sleep.moving[b] = !sleep.frozen[b] && !model.bodies[b].fixed;
  }
  broad_phase.drop_resting_pairs(sleep.moving);
}

void update_sleep(const Model& model, const std::vector<ContactPatch>& patches,
                  const ExternalLoads& loads, Real time_before, SleepWorkspace& sleep,
                  State& state) {
  const size_t n = model.bodies.size();
  if (sleep.frozen.size() != n) sleep.frozen.assign(n, 0);
  refresh_sizes(model, sleep);
  const SleepDef& def = *model.scene.sleep;

  // A wall taken away during this step: whatever rested on it must fall.
  bool gate_opened = false;
  for (const Wall& wall : model.walls)
    gate_opened = gate_opened || (time_before < wall.removed_at && wall.removed_at <= state.time);

  // Everything asleep through the step (and no wall gone): nothing changes.
  bool all_frozen = !gate_opened;
  for (size_t b = 0; b < n && all_frozen; ++b)
    all_frozen = sleep.frozen[b] || model.bodies[b].driven();
  if (all_frozen) return;

  // The woken bodies, and the rest timers of every body that moved this step.
  for (size_t b = 0; b < n; ++b) {
    BodyState& s = state.bodies[b];
    if (model.bodies[b].driven()) continue;
    if (sleep.frozen[b] && !gate_opened) continue;
    if (s.asleep) {
      s.asleep = false;
      s.island = -1;
      if (gate_opened) s.rest_time = 0;
      if (sleep.frozen[b]) continue;  // it was not integrated: no speed of its own yet
    }
    const Real speed = s.v.norm() + s.angular_velocity_world().norm() * sleep.size[b];
    if (speed < def.speed && !loaded(loads, b))
      s.rest_time += model.scene.time_step;
    else
      s.rest_time = 0;
  }

  // Islands: free awake bodies joined by this step's patches.
  std::vector<int>& parent = sleep.parent;
  parent.resize(n);
  for (size_t b = 0; b < n; ++b) parent[b] = static_cast<int>(b);
  for (const ContactPatch& p : patches) {
    if (p.body_b < 0) continue;
    if (model.bodies[p.body_a].driven() || model.bodies[p.body_b].driven()) continue;
    const int ra = find_root(parent, p.body_a), rb = find_root(parent, p.body_b);
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  // Per root: the shortest rest and the lowest id of its island.
  constexpr Real kNever = -1;
  std::vector<Real>& least_rest = sleep.least_rest;
  std::vector<long long>& name = sleep.name;
  least_rest.assign(n, std::numeric_limits<Real>::infinity());
  name.assign(n, std::numeric_limits<long long>::max());
  for (size_t b = 0; b < n; ++b) {
    const int r = find_root(parent, static_cast<int>(b));
    if (model.bodies[b].driven() || state.bodies[b].asleep) {
      least_rest[r] = kNever;  // joined to a sleeper that did not wake: not this step
      continue;
    }
    least_rest[r] = std::min(least_rest[r], state.bodies[b].rest_time);
    name[r] =
        std::min(name[r], state.tags.size() == n ? state.tags[b].id : static_cast<long long>(b));
  }
  for (size_t b = 0; b < n; ++b) {
    BodyState& s = state.bodies[b];
    if (model.bodies[b].driven() || s.asleep) continue;
    const int r = find_root(parent, static_cast<int>(b));
    if (least_rest[r] < def.time) continue;
    s.asleep = true;
    s.island = name[r];
    s.v.setZero();
    s.omega.setZero();
    // The paper integrator's torque history ends here; it starts again when the body wakes.
    s.prev_torque.setZero();
    s.has_prev_torque = false;
  }
}

void wake_near_removed(const Model& model, const std::vector<RemovedBody>& removed, size_t first,
                       State& state) {
  if (first >= removed.size() || sleeping_bodies(state) == 0) return;
  std::vector<long long> islands;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyState& s = state.bodies[b];
    if (!s.asleep) continue;
    const Real size = body_size(model, static_cast<int>(b));
    for (size_t k = first; k < removed.size(); ++k) {
      if ((s.x - removed[k].x).norm() <= 1.1 * (size + removed[k].size)) {
        islands.push_back(s.island);
        break;
      }
    }
  }
  sort_unique(islands);
  wake_islands(islands, state);
}

long long sleeping_bodies(const State& state) {
  long long count = 0;
  for (const BodyState& s : state.bodies) count += s.asleep ? 1 : 0;
  return count;
}

}  // namespace tem
