#include "contact/pair_cache.hpp"

#include <algorithm>
#include <tuple>

namespace tem {
namespace {

template <class Entry>
std::tuple<int, int, int, int> key(const Entry& e) {
  return {e.body_a, e.block_a, e.body_b, e.block_b};
}

template <class Entry>
const Entry* find_entry(const std::vector<Entry>& cache, int body_a, int block_a, int body_b,
                        int block_b) {
  Entry probe;
  probe.body_a = body_a;
  probe.block_a = block_a;
  probe.body_b = body_b;
  probe.block_b = block_b;
  const auto it = std::lower_bound(cache.begin(), cache.end(), probe,
                                   [](const Entry& x, const Entry& y) { return key(x) < key(y); });
  if (it == cache.end() || key(*it) != key(probe)) return nullptr;
  return &*it;
}

template <class Entry>
void sort_by_pair(std::vector<Entry>& cache) {
  std::sort(cache.begin(), cache.end(),
            [](const Entry& x, const Entry& y) { return key(x) < key(y); });
}

}  // namespace

void relative_pose(const BlockPose& a, const BlockPose& b, Mat3& rotation, Vec3& offset) {
  rotation = a.inverse * b.rotation;
  offset = a.inverse * (b.position - a.position);
}

const CachedFeatures* cached_features(const std::vector<CachedFeatures>& cache, int body_a,
                                      int block_a, int body_b, int block_b) {
  return find_entry(cache, body_a, block_a, body_b, block_b);
}

const CachedSeparation* cached_separation(const std::vector<CachedSeparation>& cache, int body_a,
                                          int block_a, int body_b, int block_b) {
  return find_entry(cache, body_a, block_a, body_b, block_b);
}

void sort_separations(std::vector<CachedSeparation>& cache) { sort_by_pair(cache); }

bool features_fit(const CachedFeatures& entry, const WorldBlock& a, const WorldBlock& b) {
  const auto fits = [](int index, size_t size) {
    return index >= 0 && static_cast<size_t>(index) < size;
  };
  switch (entry.feature) {
    case ManifoldFeature::edges:
      return fits(entry.feature_a, a.edge_node.size()) && fits(entry.feature_b, b.edge_node.size());
    case ManifoldFeature::face_of_a:
      return fits(entry.feature_a, a.normals.size());
    case ManifoldFeature::face_of_b:
      return fits(entry.feature_b, b.normals.size());
    default:
      return false;
  }
}

bool near_search(const CachedFeatures& entry, const Mat3& rotation, const Vec3& offset,
                 Real smaller_radius) {
  if ((offset - entry.offset).norm() > kCacheSlide * smaller_radius) return false;
  // The angle of the turn between the two relative rotations, from the trace of one applied
  // to the other's inverse: 1 + 2 cos(angle).
  const Real trace = (entry.rotation.transpose() * rotation).trace();
  return trace >= 1 + 2 * std::cos(kCacheTurn);
}

void keep_features(const std::vector<ContactPatch>& patches, std::vector<CachedFeatures>& cache) {
  cache.clear();
  for (const ContactPatch& p : patches) {
    const ManifoldFeature f = p.manifold.feature;
    if (p.wall >= 0 || p.block_b < 0 || p.manifold.count == 0) continue;
    if (f != ManifoldFeature::edges && f != ManifoldFeature::face_of_a &&
        f != ManifoldFeature::face_of_b)
      continue;
    CachedFeatures e;
    e.body_a = p.body_a;
    e.block_a = p.block_a;
    e.body_b = p.body_b;
    e.block_b = p.block_b;
    e.feature = f;
    e.feature_a = p.manifold.feature_a;
    e.feature_b = p.manifold.feature_b;
    e.rotation = p.searched_rotation;
    e.offset = p.searched_offset;
    e.beyond_rim = p.searched_beyond_rim;
    cache.push_back(e);
  }
  sort_by_pair(cache);
}

}  // namespace tem
