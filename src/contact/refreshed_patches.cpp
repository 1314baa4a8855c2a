#include "contact/refreshed_patches.hpp"

#include <algorithm>
#include <array>

#include "collision/block_pose.hpp"
#include "support/parallel.hpp"

namespace tem {

void refresh_patches(const Model& model, const State& state, const ContactWorkspace& contact,
                     const std::vector<ContactPatch>& detected, RefreshScratch& scratch,
                     std::vector<ContactPatch>& out) {
  const long long n = static_cast<long long>(detected.size());
  scratch.threads.resize(static_cast<size_t>(max_threads()));
  scratch.found.assign(detected.size(), 0);
  // Each patch is rebuilt in its own place of `out`, and those not found again are then closed
  // up: no copy of a patch where every one is found, as in a pile at rest.
  out.resize(detected.size());
  const std::vector<Real>& reach = contact.reach;
  // Each block in some patch placed once (its faces), for all its patches: a coin in a pile is
  // in five or six of them, and placing it for each was an eighth of a settled pile's step.
  std::vector<int>& first = scratch.first_block;
  first.resize(model.bodies.size() + 1);
  first[0] = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    first[b + 1] = first[b] + static_cast<int>(model.bodies[b].blocks.size());
  std::vector<int>& slot = scratch.slot;
  slot.assign(static_cast<size_t>(first.back()), -1);
  std::vector<std::array<int, 2>>& placed = scratch.placed;  // body, instance
  placed.clear();
  auto mark = [&](int body, int instance) {
    int& k = slot[static_cast<size_t>(first[body] + instance)];
    if (k >= 0) return;
    k = static_cast<int>(placed.size());
    placed.push_back({body, instance});
  };
  for (const ContactPatch& d : detected) {
    mark(d.body_a, d.block_a);
    if (d.wall < 0) mark(d.body_b, d.block_b);
  }
  scratch.world.resize(std::max(scratch.world.size(), placed.size()));
  parallel_for(static_cast<long long>(placed.size()), 64, [&](long long i) {
    const auto [body, instance] = placed[static_cast<size_t>(i)];
    place_faces(block_of(model, body, instance),
                block_placement(model.bodies[body].blocks[instance], state.bodies[body]),
                scratch.world[static_cast<size_t>(i)]);
  });
  auto world_of = [&](int body, int instance) -> const WorldBlock& {
    return scratch.world[static_cast<size_t>(slot[static_cast<size_t>(first[body] + instance)])];
  };
  parallel_for(n, 64, [&](long long k) {
    const ContactPatch& d = detected[static_cast<size_t>(k)];
    ManifoldScratch& s = scratch.threads[static_cast<size_t>(thread_index())];
    const Block& a = block_of(model, d.body_a, d.block_a);
    const WorldBlock& world_a = world_of(d.body_a, d.block_a);
    Manifold m;
    bool found;
    if (d.wall >= 0) {
      const Wall& wall = model.walls[d.wall];
      found = wall_manifold(a, world_a, wall.point, wall.normal, 2 * reach[d.body_a], s, m);
    } else {
      const Block& b = block_of(model, d.body_b, d.block_b);
      const WorldBlock& world_b = world_of(d.body_b, d.block_b);
      const Real margin = reach[d.body_a] + reach[d.body_b];
      const Rebuild rebuilt =
          rebuild_from_features(a, world_a, b, world_b, margin, d.manifold, s, m);
      found = rebuilt == Rebuild::held;
      if (rebuilt == Rebuild::search) {
        // The search reads the blocks' edges too, which only it needs: placed on this thread's
        // copies (the placed blocks are shared by the threads).
        s.a = world_a;
        s.b = world_b;
        place_edges(a, s.a);
        place_edges(b, s.b);
        found = block_manifold(a, s.a, b, s.b, margin, s, m);
      }
    }
    if (!found) return;
    ContactPatch& p = out[static_cast<size_t>(k)];
    p = manifold_patch(m);
    p.body_a = d.body_a;
    p.body_b = d.body_b;
    p.wall = d.wall;
    p.block_a = d.block_a;
    p.block_b = d.block_b;
    scratch.found[static_cast<size_t>(k)] = 1;
  });
  size_t kept = 0;
  for (size_t k = 0; k < detected.size(); ++k) {
    if (!scratch.found[k]) continue;
    if (kept != k) out[kept] = std::move(out[k]);
    ++kept;
  }
  out.resize(kept);
}

}  // namespace tem
