// Sleep of bodies at rest (the scene's `sleep`; docs/method.md "Sleep"). A body's rest timer
// (BodyState::rest_time) grows while its point speed |v| + |omega| * size stays below
// sleep.speed and restarts from zero otherwise. An island is a set of free bodies joined by
// the step's contact patches (fixed bodies, bodies with a prescribed motion and walls join
// nothing); it falls asleep when every body of it has rested for sleep.time: velocities set to
// exactly zero, the pose kept. A sleeping body is not integrated, and its pairs with other
// sleeping bodies, fixed bodies and walls are dropped after the broad phase, so they cost no
// narrow phase and no solve.
//
// Waking, before the narrow phase (so the woken bodies' contacts are all found in the step
// that wakes them): a sleeping island wakes as a whole when one of its bodies shares a
// broad-phase pair with an awake free body or a body with a prescribed motion, has an external
// load, or has a velocity (set from outside). After the population stage: bodies near a body
// taken away wake with their islands; when a wall is taken away every body wakes.
//
// Everything here runs on one thread in body and patch order, from the State alone (timers,
// flags, island names are in BodyState, so in the checkpoint): the same bits with any number
// of threads and after a resume.
#pragma once

#include <vector>

#include "collision/broad_phase.hpp"
#include "contact/contact_patch.hpp"
#include "forces/contact_forces.hpp"
#include "process/population.hpp"
#include "world/model.hpp"

namespace tem {

// What sleep keeps from one stage of a step to the next; nothing that a resume would need.
struct SleepWorkspace {
  // Per body, this step: not integrated (asleep and not woken), and moving (neither asleep
  // nor fixed). Empty: sleep is off.
  std::vector<char> frozen, moving;
  // Per body: its size (body_size), for the point speed; refreshed when the bodies change.
  std::vector<Real> size;
  long long size_version = -1;
  // Scratch: island names to wake; union-find parents, and per root the shortest rest and
  // the lowest body id of its island.
  std::vector<long long> wake, name;
  std::vector<int> parent;
  std::vector<Real> least_rest;
  bool is_frozen(size_t body) const { return !frozen.empty() && frozen[body]; }
};

// Before the broad phase: whether every free body sleeps and nothing can wake one this step
// (no prescribed motion, no load, no velocity given from outside). Then the step has no
// contact to find: `patches` are cleared and `forces` made from none, as the full stages would
// after dropping every pair, and the broad phase is skipped too. Only with the scene's `sleep`.
bool everything_sleeps(const Model& model, const State& state, const ExternalLoads& loads,
                       SleepWorkspace& sleep, std::vector<ContactPatch>& patches,
                       ContactForces& forces);

// After the broad phase: decides who wakes this step, fills `frozen` and `moving`, and drops
// the pairs in which nothing moves. Only with the scene's `sleep`.
void leave_sleepers_out(const Model& model, const State& state, const ExternalLoads& loads,
                        SleepWorkspace& sleep, BroadPhase& broad_phase);

// After integration, with the step's patches: the woken bodies' flags, the rest timers, and
// the islands that fall asleep. `time_before` is the time the step started at (a wall taken
// away during the step wakes every body).
void update_sleep(const Model& model, const std::vector<ContactPatch>& patches,
                  const ExternalLoads& loads, Real time_before, SleepWorkspace& sleep,
                  State& state);

// After bodies are taken away (removed[first..]): every sleeping body that could have touched
// one of them (centres closer than the sum of the two sizes, plus a tenth for contact before
// overlap) wakes with its island, its rest timer restarted.
void wake_near_removed(const Model& model, const std::vector<RemovedBody>& removed, size_t first,
                       State& state);

// How many bodies sleep.
long long sleeping_bodies(const State& state);

}  // namespace tem
