#include "contact/detect_contacts.hpp"

#include <algorithm>

namespace tem {

PatchVariant patch_variant(const SceneDef& scene) {
  return scene.contact.normals == PatchNormals::paper ? NormalVariant::paper
                                                     : NormalVariant::default_;
}

void detect_contacts(const Model& model, const State& state, PatchVariant variant,
                     ContactWorkspace& w, std::vector<ContactPatch>& patches) {
  // 1. Broad phase: candidate block pairs and block-wall pairs from world bounds.
  w.broad_phase.update(model, state);
  find_patches(model, variant, w, patches);
}

void find_patches(const Model& model, PatchVariant variant, ContactWorkspace& w,
                  std::vector<ContactPatch>& patches) {
  patches.clear();
  const std::vector<BlockProxy>& proxies = w.broad_phase.proxies();
  const std::vector<BlockPose>& poses = w.broad_phase.poses();
  auto block_of = [&](int proxy) -> const Block& {
    const BlockProxy& p = proxies[proxy];
    return model.blocks[model.bodies[p.body].blocks[p.instance].block];
  };

  // 2-3. Narrow phase and patches, pair by pair.
  for (const BlockPair& pair : w.broad_phase.block_pairs()) {
    const Block &a = block_of(pair.a), &b = block_of(pair.b);
    if (!block_pair_features(a, poses[pair.a], b, poses[pair.b], w.narrow, w.pair)) continue;
    const size_t first = patches.size();
    pair_patches(a, poses[pair.a], b, poses[pair.b], w.pair, variant, w.patch, patches);
    for (size_t k = first; k < patches.size(); ++k) {
      patches[k].body_a = proxies[pair.a].body;
      patches[k].body_b = proxies[pair.b].body;
    }
  }
  for (const WallPair& pair : w.broad_phase.wall_pairs()) {
    const Wall& wall = model.walls[pair.wall];
    const Block& block = block_of(pair.proxy);
    block_wall_features(block, poses[pair.proxy], wall.point, wall.normal, w.wall);
    const size_t first = patches.size();
    wall_patches(block, poses[pair.proxy], wall.point, wall.normal, w.wall, variant, w.patch,
                 patches);
    for (size_t k = first; k < patches.size(); ++k) {
      patches[k].body_a = proxies[pair.proxy].body;
      patches[k].wall = pair.wall;
    }
  }

  // One patch per place: blocks of one body touching the other body at one place merge.
  std::stable_sort(patches.begin(), patches.end(),
                   [](const ContactPatch& p, const ContactPatch& q) {
                     const bool pw = p.wall >= 0, qw = q.wall >= 0;
                     if (p.body_a != q.body_a) return p.body_a < q.body_a;
                     if (pw != qw) return qw;
                     return pw ? p.wall < q.wall : p.body_b < q.body_b;
                   });
  merge_touching_patches(patches);
}

}  // namespace tem
