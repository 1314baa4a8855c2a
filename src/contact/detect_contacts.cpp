#include "contact/detect_contacts.hpp"

#include <algorithm>

#include "world/parallel.hpp"

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
  const std::vector<BlockPair>& block_pairs = w.broad_phase.block_pairs();
  const std::vector<WallPair>& wall_pairs = w.broad_phase.wall_pairs();
  auto block_of = [&](int proxy) -> const Block& {
    const BlockProxy& p = proxies[proxy];
    return model.blocks[model.bodies[p.body].blocks[p.instance].block];
  };

  // 2-3. Narrow phase and patches, pair by pair: block pairs, then block-wall pairs, as one
  // list cut into runs of kRun pairs that threads take in turn.
  constexpr long long kRun = 32;
  const long long n_block = static_cast<long long>(block_pairs.size());
  const long long n_all = n_block + static_cast<long long>(wall_pairs.size());
  const long long runs = (n_all + kRun - 1) / kRun;
  w.threads.resize(static_cast<size_t>(max_threads()));

  // Tests items [begin, end) in order, appending their patches to `out`.
  auto test_items = [&](long long begin, long long end, PairScratch& s,
                        std::vector<ContactPatch>& out) {
    for (long long item = begin; item < end; ++item) {
      const size_t first = out.size();
      if (item < n_block) {
        const BlockPair& pair = block_pairs[static_cast<size_t>(item)];
        const Block &a = block_of(pair.a), &b = block_of(pair.b);
        if (!block_pair_features(a, poses[pair.a], b, poses[pair.b], s.narrow, s.pair)) continue;
        pair_patches(a, poses[pair.a], b, poses[pair.b], s.pair, variant, s.patch, out);
        for (size_t k = first; k < out.size(); ++k) {
          out[k].body_a = proxies[pair.a].body;
          out[k].body_b = proxies[pair.b].body;
        }
      } else {
        const WallPair& pair = wall_pairs[static_cast<size_t>(item - n_block)];
        const Wall& wall = model.walls[pair.wall];
        const Block& block = block_of(pair.proxy);
        block_wall_features(block, poses[pair.proxy], wall.point, wall.normal, s.wall);
        wall_patches(block, poses[pair.proxy], wall.point, wall.normal, s.wall, variant, s.patch,
                     out);
        for (size_t k = first; k < out.size(); ++k) {
          out[k].body_a = proxies[pair.proxy].body;
          out[k].wall = pair.wall;
        }
      }
    }
  };
  if (w.threads.size() == 1 || runs <= 1) {
    // One thread: straight into the result, in the same order the runs would give.
    test_items(0, n_all, w.threads[0], patches);
  } else {
    if (w.chunks.size() < static_cast<size_t>(runs)) w.chunks.resize(static_cast<size_t>(runs));
    parallel_for(runs, 1, [&](long long run) {
      std::vector<ContactPatch>& out = w.chunks[static_cast<size_t>(run)];
      out.clear();
      test_items(run * kRun, std::min(n_all, (run + 1) * kRun),
                 w.threads[static_cast<size_t>(thread_index())], out);
    }, /*dynamic=*/true);
    for (long long run = 0; run < runs; ++run)
      for (ContactPatch& p : w.chunks[static_cast<size_t>(run)]) patches.push_back(std::move(p));
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
