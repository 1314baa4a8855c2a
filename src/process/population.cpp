#include "process/population.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "process/motion.hpp"
#include "world/fill.hpp"
#include "world/inlet_delivery.hpp"
#include "world/placement.hpp"

namespace tem {
namespace {

// Draws of a copy's place and orientation tried per step before it waits for the next.
constexpr int kAttemptsPerStep = 50;
// Streams of an inlet's generator.
constexpr std::uint64_t kScaleStream = 1, kPlaceStream = 2;

// splitmix64 (Steele, Lea and Flood 2014): a well-mixed 64-bit value from any counter.
std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from the top 53 bits of the counter's value.
Real draw(std::uint64_t seed, std::uint64_t stream, std::uint64_t counter) {
  const std::uint64_t z = splitmix64(splitmix64(splitmix64(seed) ^ stream) ^ counter);
  return static_cast<Real>(z >> 11) * 0x1.0p-53;
}

Real copy_scale(const InletDef& inlet, long long copy) {
  if (!inlet.body.scale) return 1;
  const ScaleDef& s = *inlet.body.scale;
  return s.min + draw(inlet.seed, kScaleStream, static_cast<std::uint64_t>(copy)) * (s.max - s.min);
}

// Copy `copy` of inlet `j` at size factor `scale` (its pose is set by whoever places it).
Body inlet_copy(Model& model, int j, long long copy, Real scale) {
  const InletDef& inlet = model.scene.inlets[j];
  Body body = scale == 1 ? model.inlet_templates[j] : build_body(inlet.body, model, scale);
  body.name = inlet.name + "_" + std::to_string(copy);
  body.start_velocity = inlet.velocity;
  body.force_sensors = force_sensors_naming(model.scene, body.name);
  return body;
}

// Whether a sphere is clear of the walls present at time t and of every body.
bool room_for(const Model& model, const State& state, const std::vector<Real>& sizes,
              const Vec3& centre, Real radius) {
  for (const Wall& wall : model.walls)
    if (state.time < wall.removed_at && wall.normal.dot(centre - wall.point) < radius) return false;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if ((state.bodies[b].x - centre).norm() >= radius + sizes[b]) continue;
    if (!sphere_clear_of_body(model, model.bodies[b], state.bodies[b], centre, radius)) return false;
  }
  return true;
}

// Renumbers the contact memory after removal (map: old body -> new, -1 for gone), dropping
// every entry that touched a body that left. Monotone renumbering keeps the pair order the
// warm start and the penalty springs rely on.
void renumber_memory(const Model& model, const std::vector<int>& map,
                     const PopulationLinks& links) {
  if (links.patches) {
    std::vector<ContactPatch>& patches = *links.patches;
    std::vector<PatchForce>* forces = links.forces ? &links.forces->patch_forces : nullptr;
    const bool parallel = forces && forces->size() == patches.size();
    size_t next = 0;
    for (size_t k = 0; k < patches.size(); ++k) {
      if (pair_gone(map, patches[k].body_a, patches[k].body_b)) continue;
      patches[next] = patches[k];
      renumber_pair(map, patches[next].body_a, patches[next].body_b);
      if (parallel) (*forces)[next] = (*forces)[k];
      ++next;
    }
    patches.resize(next);
    if (parallel) forces->resize(next);
  }
  if (links.features) {
    std::erase_if(*links.features,
                  [&](const CachedFeatures& e) { return pair_gone(map, e.body_a, e.body_b); });
    for (CachedFeatures& e : *links.features) renumber_pair(map, e.body_a, e.body_b);
  }
  if (!links.forces) return;
  // The force model's memory (force_model.hpp): its records of the bodies gone dropped, the
  // others renumbered.
  const ForceModel& force = force_model(model.scene.contact);
  std::vector<MemoryRecord> memory;
  force.save_memory(*links.forces, memory);
  renumber_records(map, memory);
  force.load_memory(memory, *links.forces);
}

// Takes away the bodies that leave at state.time; whether any did.
bool remove_leaving(Model& model, State& state, const PopulationLinks& links,
                    std::vector<RemovedBody>& removed) {
  const std::vector<OutletDef>& outlets = model.scene.outlets;
  const size_t n = model.bodies.size();
  std::vector<int> map(n, -1);
  int kept = 0;
  for (size_t b = 0; b < n; ++b) {
    const Body& body = model.bodies[b];
    const BodyState& s = state.bodies[b];
    bool leaves = !(state.time < body.removed_at);
    if (!body.driven())
      for (const OutletDef& o : outlets) leaves = leaves || o.region.contains(s.x);
    if (!leaves) {
      map[b] = kept++;
      continue;
    }
    removed.push_back({state.time, body.name, s.x, s.v, body.inertia.mass,
                       model.scene.sleep ? body_size(model, body) : 0});
    if (body.owns_blocks)
      for (const BlockInstance& i : body.blocks) model.free_blocks.push_back(i.block);
  }
  if (kept == static_cast<int>(n)) return false;
  ExternalLoads* loads = links.loads;
  const bool with_loads = loads && loads->force.size() == n;
  for (size_t b = 0; b < n; ++b) {
    const int to = map[b];
    if (to < 0 || to == static_cast<int>(b)) continue;
    model.bodies[to] = std::move(model.bodies[b]);
    state.bodies[to] = state.bodies[b];
    state.tags[to] = state.tags[b];
    if (with_loads) {
      loads->force[to] = loads->force[b];
      loads->torque[to] = loads->torque[b];
    }
  }
  model.bodies.resize(kept);
  state.bodies.resize(kept);
  state.tags.resize(kept);
  if (with_loads) {
    loads->force.resize(kept);
    loads->torque.resize(kept);
    loads->update_active();
  }
  renumber_memory(model, map, links);
  return true;
}

// Adds the copies each inlet owes by state.time, as far as they find room; whether any was.
bool insert_due(Model& model, State& state, const PopulationLinks& links) {
  const std::vector<InletDef>& inlets = model.scene.inlets;
  state.inlets.resize(inlets.size());
  std::vector<Real> sizes;  // of the bodies present, computed once a copy is due
  bool added = false;
  for (size_t j = 0; j < inlets.size(); ++j) {
    const InletDef& inlet = inlets[j];
    InletProgress& progress = state.inlets[j];
    const long long due = copies_due(inlet, state.time);
    while (progress.placed < due) {
      if (sizes.size() != model.bodies.size()) {
        sizes.resize(model.bodies.size());
        for (size_t b = 0; b < sizes.size(); ++b) sizes[b] = body_size(model, static_cast<int>(b));
      }
      const long long k = progress.placed;
      const Real scale = copy_scale(inlet, k);
      const Real radius = scale * body_size(model, model.inlet_templates[j]);
      bool placed = false;
      for (int attempt = 0; attempt < kAttemptsPerStep && !placed; ++attempt) {
        auto next = [&] { return draw(inlet.seed, kPlaceStream, progress.draws++); };
        Vec3 centre;
        for (int a = 0; a < 3; ++a) {
          const Real lo = inlet.region.min[a] + radius, hi = inlet.region.max[a] - radius;
          centre[a] = lo + next() * (hi - lo);
        }
        const Real u1 = next(), u2 = next(), u3 = next();
        if (!room_for(model, state, sizes, centre, radius)) continue;
        Body body = inlet_copy(model, static_cast<int>(j), k, scale);
        const Mat3 rotation = uniform_rotation(u1, u2, u3);
        body.start_rotation = rotation;
        body.start_position = centre + rotation * body.origin_offset;
        BodyState s;
        s.x = centre;
        s.g = rotation;
        s.v = inlet.velocity;
        s.omega = rotation.transpose() * body.start_angular_velocity;
        sizes.push_back(body_size(model, body));
        model.bodies.push_back(std::move(body));
        state.bodies.push_back(s);
        state.tags.push_back({state.next_id++, static_cast<int>(j), static_cast<int>(k), scale});
        if (links.loads && links.loads->force.size() + 1 == model.bodies.size()) {
          links.loads->force.push_back(Vec3::Zero());
          links.loads->torque.push_back(Vec3::Zero());
        }
        placed = true;
      }
      if (!placed) break;  // no room this step: it waits, counted late
      ++progress.placed;
      added = true;
    }
  }
  return added;
}

}  // namespace

size_t population_capacity(const Model& model) {
  size_t n = model.bodies.size();
  for (const InletDef& inlet : model.scene.inlets) n += static_cast<size_t>(inlet.count);
  return n;
}

void start_population(Model& model, State& state, const PopulationLinks& links,
                      std::vector<RemovedBody>& removed) {
  if (model.any_motion) move_driven_bodies(model, state, substep_time(model.scene));
  if (model.bodies_come_and_go) update_population(model, state, links, removed);
}

void update_population(Model& model, State& state, const PopulationLinks& links,
                       std::vector<RemovedBody>& removed) {
  bool changed = remove_leaving(model, state, links, removed);
  changed = insert_due(model, state, links) || changed;
  if (changed) ++model.population_version;
}

void restore_population(Model& model, const std::vector<Body>& initial, const State& state) {
  if (state.tags.size() != state.bodies.size())
    throw std::runtime_error("its bodies and their tags disagree");
  std::vector<Body> live;
  live.reserve(state.tags.size());
  for (const BodyTag& tag : state.tags) {
    if (tag.inlet < 0) {
      if (tag.id < 0 || static_cast<size_t>(tag.id) >= initial.size())
        throw std::runtime_error("it names body id " + std::to_string(tag.id) +
                                 ", which the scene does not have");
      live.push_back(initial[static_cast<size_t>(tag.id)]);
    } else {
      if (static_cast<size_t>(tag.inlet) >= model.scene.inlets.size())
        throw std::runtime_error("it names inlet " + std::to_string(tag.inlet) +
                                 ", which the scene does not have");
      live.push_back(inlet_copy(model, tag.inlet, tag.copy, tag.scale));
    }
  }
  model.bodies = std::move(live);
  ++model.population_version;
}

}  // namespace tem
