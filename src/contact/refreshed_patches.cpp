#include "contact/refreshed_patches.hpp"

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
  parallel_for(n, 64, [&](long long k) {
    const ContactPatch& d = detected[static_cast<size_t>(k)];
    ManifoldScratch& s = scratch.threads[static_cast<size_t>(thread_index())];
    const BlockInstance& instance_a = model.bodies[d.body_a].blocks[d.block_a];
    const Block& a = block_of(model, d.body_a, d.block_a);
    // The edges are placed only where the search must answer: most patches are rebuilt from
    // a face's clip, which reads none of them.
    place_faces(a, block_placement(instance_a, state.bodies[d.body_a]), s.a);
    Manifold m;
    bool found;
    if (d.wall >= 0) {
      const Wall& wall = model.walls[d.wall];
      found = wall_manifold(a, s.a, wall.point, wall.normal, 2 * reach[d.body_a], s, m);
    } else {
      const BlockInstance& instance_b = model.bodies[d.body_b].blocks[d.block_b];
      const Block& b = block_of(model, d.body_b, d.block_b);
      place_faces(b, block_placement(instance_b, state.bodies[d.body_b]), s.b);
      const Real margin = reach[d.body_a] + reach[d.body_b];
      const Rebuild rebuilt = rebuild_from_features(a, s.a, b, s.b, margin, d.manifold, s, m);
      found = rebuilt == Rebuild::held;
      if (rebuilt == Rebuild::search) {
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
