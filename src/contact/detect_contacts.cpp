#include "contact/detect_contacts.hpp"

#include <algorithm>

#include "support/parallel.hpp"

namespace tem {

ContactPatch manifold_patch(const Manifold& m) {
  ContactPatch p;
  p.normal = m.normal;
  p.manifold = m;
  p.features = m.count;
  p.bounds_min = p.bounds_max = m.point[0];
  Real smallest_gap = m.gap[0];
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < m.count; ++k) {
    sum += m.point[k];
    smallest_gap = std::min(smallest_gap, m.gap[k]);
    p.bounds_min = p.bounds_min.cwiseMin(m.point[k]);
    p.bounds_max = p.bounds_max.cwiseMax(m.point[k]);
  }
  p.point = sum / m.count;
  p.depth = -smallest_gap;
  return p;
}

namespace {

// A block pair with contact before overlap: its patch where the blocks are within their margin
// (false otherwise), from last step's features where the pair has barely moved since they were
// searched and they still hold, skipped where last step's separating face still keeps it apart,
// else from the whole search (pair_cache.hpp); what it learns goes into the thread's scratch.
bool patch_ahead(const ContactWorkspace& w, const BlockPair& pair, const Block& a, const Block& b,
                 PairScratch& s, ContactPatch& p) {
  const std::vector<BlockProxy>& proxies = w.broad_phase.proxies();
  const std::vector<BlockPose>& poses = w.broad_phase.poses();
  const WorldBlock &world_a = w.world[pair.a], &world_b = w.world[pair.b];
  const int body_a = proxies[pair.a].body, body_b = proxies[pair.b].body;
  const int block_a = proxies[pair.a].instance, block_b = proxies[pair.b].instance;
  const Real margin = w.reach[body_a] + w.reach[body_b];
  ++s.pairs_tested;
  Mat3 rotation = Mat3::Identity();
  Vec3 offset = Vec3::Zero();
  const CachedFeatures* cached = nullptr;
  if (w.use_features) {
    relative_pose(poses[pair.a], poses[pair.b], rotation, offset);
    cached = cached_features(w.features, body_a, block_a, body_b, block_b);
    if (cached && (!features_fit(*cached, world_a, world_b) ||
                   !near_search(*cached, rotation, offset,
                                std::min(a.bounding_radius(), b.bounding_radius()))))
      cached = nullptr;
    const CachedSeparation* apart =
        cached ? nullptr : cached_separation(w.separations, body_a, block_a, body_b, block_b);
    if (apart && still_separated(world_a, world_b, apart->face, margin)) {
      ++s.pairs_apart;
      s.separations.push_back(*apart);
      return false;
    }
  }
  Manifold m;
  SeparatingFace separated;
  bool found, searched = true;
  if (cached) {
    Manifold features;
    features.feature = cached->feature;
    features.feature_a = cached->feature_a;
    features.feature_b = cached->feature_b;
    features.beyond_rim = cached->beyond_rim;
    found = rebuild_manifold(a, world_a, b, world_b, margin, features, s.manifold, m, &searched);
    if (!searched) ++s.pairs_cached;
  } else {
    found = block_manifold(a, world_a, b, world_b, margin, s.manifold, m, &separated);
  }
  if (!found) {
    if (w.use_features && separated.side != ManifoldFeature::none)
      s.separations.push_back({body_a, block_a, body_b, block_b, separated});
    return false;
  }
  p = manifold_patch(m);
  p.body_a = body_a;
  p.body_b = body_b;
  p.block_a = block_a;
  p.block_b = block_b;
  p.searched_rotation = searched ? rotation : cached->rotation;
  p.searched_offset = searched ? offset : cached->offset;
  p.searched_beyond_rim = searched ? m.beyond_rim : cached->beyond_rim;
  return true;
}

}  // namespace

PatchVariant patch_variant(const SceneDef& scene) {
  return scene.contact.normals == PatchNormals::paper ? NormalVariant::paper
                                                     : NormalVariant::default_;
}

void detect_contacts(const Model& model, const State& state, PatchVariant variant,
                     ContactWorkspace& w, std::vector<ContactPatch>& patches) {
  // 1. Broad phase: candidate block pairs and block-wall pairs from world bounds.
  w.broad_phase.update(model, state, w.reach);
  find_patches(model, variant, w, patches);
}

void find_patches(const Model& model, PatchVariant variant, ContactWorkspace& w,
                  std::vector<ContactPatch>& patches) {
  patches.clear();
  const std::vector<BlockProxy>& proxies = w.broad_phase.proxies();
  const std::vector<BlockPose>& poses = w.broad_phase.poses();
  const std::vector<BlockPair>& block_pairs = w.broad_phase.block_pairs();
  const std::vector<WallPair>& wall_pairs = w.broad_phase.wall_pairs();
  auto proxy_block = [&](int proxy) -> const Block& {
    return block_of(model, proxies[proxy].body, proxies[proxy].instance);
  };

  // 2-3. Narrow phase and patches, pair by pair: block pairs, then block-wall pairs, as one
  // list cut into runs of kRun pairs that threads take in turn.
  constexpr long long kRun = 32;
  const long long n_block = static_cast<long long>(block_pairs.size());
  const long long n_all = n_block + static_cast<long long>(wall_pairs.size());
  const long long runs = (n_all + kRun - 1) / kRun;
  w.threads.resize(static_cast<size_t>(max_threads()));
  for (PairScratch& s : w.threads) {
    s.pairs_tested = s.pairs_cached = s.pairs_apart = 0;
    s.separations.clear();
  }
  const bool ahead = !w.reach.empty();
  if (ahead) {
    // Each block's world nodes, planes and edges once, for all the pairs it is in; blocks in
    // no pair (bodies in flight) are not placed at all.
    w.world.resize(proxies.size());
    w.in_pair.assign(proxies.size(), 0);
    for (const BlockPair& pair : block_pairs) w.in_pair[pair.a] = w.in_pair[pair.b] = 1;
    for (const WallPair& pair : wall_pairs) w.in_pair[pair.proxy] = 1;
    parallel_for(static_cast<long long>(proxies.size()), 256, [&](long long i) {
      if (w.in_pair[i]) place_block(proxy_block(static_cast<int>(i)), poses[i], w.world[i]);
    });
  }

  // Tests items [begin, end) in order, appending their patches to `out`.
  auto test_items = [&](long long begin, long long end, PairScratch& s,
                        std::vector<ContactPatch>& out) {
    for (long long item = begin; item < end; ++item) {
      const size_t first = out.size();
      if (item < n_block) {
        const BlockPair& pair = block_pairs[static_cast<size_t>(item)];
        const Block &a = proxy_block(pair.a), &b = proxy_block(pair.b);
        if (ahead) {
          ContactPatch p;
          if (patch_ahead(w, pair, a, b, s, p)) out.push_back(std::move(p));
          continue;
        }
        if (!block_pair_features(a, poses[pair.a], b, poses[pair.b], s.narrow, s.pair)) continue;
        pair_patches(a, poses[pair.a], b, poses[pair.b], s.pair, variant, s.patch, out);
        for (size_t k = first; k < out.size(); ++k) {
          out[k].body_a = proxies[pair.a].body;
          out[k].body_b = proxies[pair.b].body;
        }
      } else {
        const WallPair& pair = wall_pairs[static_cast<size_t>(item - n_block)];
        const Wall& wall = model.walls[pair.wall];
        const Block& block = proxy_block(pair.proxy);
        if (ahead) {
          const int body = proxies[pair.proxy].body;
          Manifold m;
          if (wall_manifold(block, w.world[pair.proxy], wall.point, wall.normal, 2 * w.reach[body],
                            s.manifold, m)) {
            out.push_back(manifold_patch(m));
            out.back().body_a = body;
            out.back().wall = pair.wall;
            out.back().block_a = proxies[pair.proxy].instance;
          }
          continue;
        }
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
  // Sorted through an index with the found order as the last key: the order std::stable_sort
  // gives, without its temporary buffer (allocated at every call).
  w.order.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k) w.order[k] = static_cast<int>(k);
  std::sort(w.order.begin(), w.order.end(), [&](int i, int j) {
    const auto p = pair_key(patches[static_cast<size_t>(i)]);
    const auto q = pair_key(patches[static_cast<size_t>(j)]);
    return p != q ? p < q : i < j;
  });
  if (w.sorted.size() < patches.size()) w.sorted.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k)
    std::swap(w.sorted[k], patches[static_cast<size_t>(w.order[k])]);
  for (size_t k = 0; k < patches.size(); ++k) std::swap(patches[k], w.sorted[k]);
  // (Patches of contact before overlap stay one per block pair: each is one face-on-face or
  // edge-on-edge place with its own normal.)
  if (!ahead) merge_touching_patches(patches);
  // The pair cache for the next step, and the counts of how this one was answered.
  const bool cache = ahead && w.use_features;
  if (cache) {
    keep_features(patches, w.features);
    w.separations.clear();
  }
  w.pairs_tested = w.pairs_cached = w.pairs_apart = 0;
  for (const PairScratch& s : w.threads) {
    w.pairs_tested += s.pairs_tested;
    w.pairs_cached += s.pairs_cached;
    w.pairs_apart += s.pairs_apart;
    if (cache)
      w.separations.insert(w.separations.end(), s.separations.begin(), s.separations.end());
  }
  if (cache) sort_separations(w.separations);
}

}  // namespace tem
