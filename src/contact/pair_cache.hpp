// The features of last step's block pairs, kept for the next step (contact.pair_cache).
//
// Why: in a settled pile the separating-axis search (every face of both blocks and every pair
// of their edges) is most of a step's narrow phase, yet from one step to the next it finds the
// same reference face or edge pair for almost every pair. A pair whose blocks have barely turned
// or moved against each other since its features were searched takes them again and only
// redoes the clip or the closest points (rebuild_manifold, as a sub-step does); the features are
// checked there to still be the supports, and the full search runs where they are not, where
// the pair is new, and where the pair has turned or slid past the limits below since the last
// full search (measured from that search, so that small moves do not add up). Jolt and Box3D
// keep contact manifolds between steps the same way.
//
// The cache changes which search answers a pair, so it is part of the state a resumed run needs
// to be bit-identical: the checkpoint keeps it (io/checkpoint.hpp). Over MPI ranks it is not
// used (the ranks' checkpoints do not hold it).
#pragma once

#include <vector>

#include "collision/block_manifold.hpp"
#include "collision/block_pose.hpp"
#include "contact/contact_patch.hpp"

namespace tem {

// One block pair's features and the blocks' relative pose when they were searched. Plain
// numbers only: written to checkpoints as they are.
struct CachedFeatures {
  // Block instances of the bodies; bodies that leave take their entries with them, the others
  // are renumbered as the rest of the contact memory (process/population.cpp).
  int body_a = -1, block_a = -1, body_b = -1, block_b = -1;
  ManifoldFeature feature = ManifoldFeature::none;
  int feature_a = -1, feature_b = -1;
  Mat3 rotation = Mat3::Identity();  // B's block frame in A's block frame at the search
  Vec3 offset = Vec3::Zero();
  // A face's node past the rim at the search (Manifold::beyond_rim): the features hold while
  // it lies no deeper. Kept from the search, not from the last rebuild, so that it cannot creep
  // deeper by round-off from step to step.
  Real beyond_rim = 0;
};

// A block pair that a face axis kept beyond its margin last step. Not in checkpoints: a pair
// whose cached face still separates it is one the whole search would also find apart (the same
// arithmetic, block_manifold.hpp still_separated), so the cache changes the cost, never a bit.
// Entries are not renumbered when bodies leave: an entry that lands on another pair is checked
// like any other and only saves a search where that face separates the pair.
struct CachedSeparation {
  int body_a = -1, block_a = -1, body_b = -1, block_b = -1;
  SeparatingFace face;
};

// The entry of the block pair, or nullptr; `cache` sorted by sort_separations.
const CachedSeparation* cached_separation(const std::vector<CachedSeparation>& cache, int body_a,
                                          int block_a, int body_b, int block_b);
void sort_separations(std::vector<CachedSeparation>& cache);

// Limits on the relative motion since the search: 0.02 rad of turn, 2% of the smaller block's
// bounding radius of slide. A turn of the reference face by more could let another face or edge
// pair become the least-separating axis; within them the kept features still support the
// blocks (rebuild_manifold checks that) and the search would pick them again or an axis whose
// separation differs by round-off.
constexpr Real kCacheTurn = 0.02;
constexpr Real kCacheSlide = 0.02;

// B's block relative to A's: the rotation and the offset of its centroid, in A's block frame.
void relative_pose(const BlockPose& a, const BlockPose& b, Mat3& rotation, Vec3& offset);

// The entry of the block pair (body_a, block_a)-(body_b, block_b), or nullptr. `cache` sorted
// as keep_features leaves it.
const CachedFeatures* cached_features(const std::vector<CachedFeatures>& cache, int body_a,
                                      int block_a, int body_b, int block_b);

// Whether the entry's feature indices exist in the placed blocks (a checkpoint's entry is
// checked against the scene it resumes).
bool features_fit(const CachedFeatures& entry, const WorldBlock& a, const WorldBlock& b);

// Whether the pair's relative pose is still within the limits of its entry's search.
bool near_search(const CachedFeatures& entry, const Mat3& rotation, const Vec3& offset,
                 Real smaller_radius);

// The cache for the next step: the features of every block-pair patch of contact before
// overlap in `patches`, with the relative pose of the search that found them.
void keep_features(const std::vector<ContactPatch>& patches, std::vector<CachedFeatures>& cache);

}  // namespace tem
