// Steps 1-3 of a simulation step (architecture.md): broad phase, narrow phase, patches. From a
// state to the list of contact patches between bodies and between bodies and walls.
#pragma once

#include <vector>

#include "collision/broad_phase.hpp"
#include "collision/narrow_phase.hpp"
#include "contact/pair_cache.hpp"
#include "contact/contact_patch.hpp"
#include "contact/patches.hpp"
#include "world/model.hpp"

namespace tem {

// The scene's contact.normals: the paper's node/edge-normal rule or the face-based default.
PatchVariant patch_variant(const SceneDef& scene);

// What one thread needs to test a pair: scratch of the narrow phase and of the patches, on
// cache lines of its own (its counters and vectors' ends change at every pair).
struct alignas(64) PairScratch {
  NarrowPhaseScratch narrow;
  PairFeatures pair;
  WallFeatures wall;
  PatchScratch patch;
  long long pairs_tested = 0, pairs_cached = 0, pairs_apart = 0;  // (ContactWorkspace's)
  std::vector<CachedSeparation> separations;  // this step's pairs a face kept apart
  ManifoldScratch manifold;
};

// Everything contact detection reuses from one step to the next.
struct ContactWorkspace {
  BroadPhase broad_phase;
  std::vector<PairScratch> threads;                // one per OpenMP thread
  std::vector<std::vector<ContactPatch>> chunks;  // the patches of each run of pairs
  // Per body, how far ahead of overlap it makes contact (contact_margins.hpp); empty: contact
  // only after overlap, by the paper's tests.
  std::vector<Real> reach;
  std::vector<WorldBlock> world;  // the blocks placed for this step (contact before overlap)
  std::vector<char> in_pair;      // per block: in some pair this step, so placed
  // The pair cache (pair_cache.hpp): the features of the last find_patches' block pairs, and
  // whether find_patches takes them and keeps this step's (set per step by its caller).
  std::vector<CachedFeatures> features;
  std::vector<CachedSeparation> separations;  // last step's pairs a face kept apart
  bool use_features = false;
  // Of the last find_patches: block pairs tested with contact before overlap, how many of them
  // took cached features that still held, and how many a cached face still kept apart (neither
  // searched).
  long long pairs_tested = 0, pairs_cached = 0, pairs_apart = 0;
  std::vector<int> order;                  // sorting the patches by body pair
  std::vector<ContactPatch> sorted;        // the patches in that order, swapped with the result
};

// Narrow phase and patches for the pairs of the workspace's last broad-phase update: with the
// workspace's reach, patches of contact before overlap (block_manifold.hpp), else the paper's
// overlap tests and grouping (narrow_phase.hpp, patches.hpp). Patches
// ordered by body pair (walls after bodies, by wall index), deterministic: the pairs are shared
// among OpenMP threads in runs, each run's patches kept apart and joined in pair order, so the
// result is the same, bit for bit, with any number of threads.
void find_patches(const Model& model, PatchVariant variant, ContactWorkspace& workspace,
                  std::vector<ContactPatch>& patches);

// Broad phase, then find_patches.
void detect_contacts(const Model& model, const State& state, PatchVariant variant,
                     ContactWorkspace& workspace, std::vector<ContactPatch>& patches);

}  // namespace tem
