// The bodies that come and go (docs/processes.md): inlets add copies of a template at a rate,
// outlets take away free bodies whose centre of mass enters their region, and `removed_at`
// takes a body away at a time (a silo's gate). Stage 0 of a step (architecture.md); TEM runs it
// at the end of each step, for the state that step leaves, so that every state a row or a
// checkpoint sees has already been through it.
//
// How the arrays change: removed bodies are taken out by one pass that keeps the others in
// order (ids stay increasing along the arrays, so output rows stay in id order), and the
// contact memory that warm-starts the next step (points, impulses, patch friction, penalty
// springs) is renumbered by the same map, its entries with a removed body dropped; new bodies
// are appended. The work is proportional to the bodies and contacts that exist, and nothing is
// done on a step where nobody comes or goes.
//
// Inlet placement: a copy is placed where its bounding sphere lies inside the inlet's region,
// on the inner side of every wall, and clear of every body's blocks (world/placement.hpp), at a
// uniform random orientation. Its random numbers come from a counter-based generator (splitmix64
// of the seed, a stream and a counter), so an inlet's whole state is two counters and a resumed
// run draws the same numbers. A copy's size factor is drawn from its own number alone: one that
// finds no room is tried again next step with the same size (no bias towards small copies in a
// crowded inlet).
#pragma once

#include <string>
#include <vector>

#include "contact/contact_patch.hpp"
#include "contact/pair_cache.hpp"
#include "forces/contact_forces.hpp"
#include "world/model.hpp"

namespace tem {

// A body that left: its last state, for removed.csv.
struct RemovedBody {
  Real time = 0;
  std::string name;
  Vec3 x = Vec3::Zero(), v = Vec3::Zero();
  Real mass = 0;
  Real size = 0;  // body_size, with the scene's `sleep` only: who rested on it wakes
};

// What the population stage changes besides the Model and the State: the contact memory and
// the external loads, which follow the bodies.
struct PopulationLinks {
  ContactForces* forces = nullptr;
  std::vector<ContactPatch>* patches = nullptr;
  ExternalLoads* loads = nullptr;
  std::vector<CachedFeatures>* features = nullptr;  // the pair cache (contact/pair_cache.hpp)
};

// The most bodies the run can hold at once: those at the start and every inlet's count.
size_t population_capacity(const Model& model);

// At the start of a run, on the initial state: puts bodies with a prescribed motion on their
// path and runs the population stage at time 0.
void start_population(Model& model, State& state, const PopulationLinks& links,
                      std::vector<RemovedBody>& removed);

// Stage 0: removal (outlets, removed_at), then insertion (inlets), at state.time. Appends the
// bodies taken away to `removed`.
void update_population(Model& model, State& state, const PopulationLinks& links,
                       std::vector<RemovedBody>& removed);

// model.bodies for a checkpoint's state: `initial` are the bodies at the start (ids 0, 1, ...),
// inlet copies are rebuilt from their tags. Throws std::runtime_error when the tags do not fit
// the scene.
void restore_population(Model& model, const std::vector<Body>& initial, const State& state);

}  // namespace tem
