#include "collision/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "support/parallel.hpp"

namespace tem {
namespace {

constexpr int kCellBits = 21;                   // per axis in a cell key
constexpr Real kMaxCellsPerAxis = 1 << 20;      // leaves room below 2^21 after flooring
constexpr long long kMaxCellsPerBlock = 64;     // more: the block goes on the large list

unsigned long long cell_key(long long ix, long long iy, long long iz) {
  return static_cast<unsigned long long>(ix) |
         (static_cast<unsigned long long>(iy) << kCellBits) |
         (static_cast<unsigned long long>(iz) << (2 * kCellBits));
}

}  // namespace

Aabb block_bounds(const Block& block, const BlockPose& pose) {
  Aabb box = Aabb::empty();
  for (const Vec3& node : block.nodes()) box.add(pose.to_world(node));
  return box;
}

void BroadPhase::build_proxies(const Model& model, const BodySubset* subset) {
  proxies_.clear();
  for (int b = 0; b < static_cast<int>(model.bodies.size()); ++b) {
    if (subset && !subset->resident[b]) continue;
    for (int i = 0; i < static_cast<int>(model.bodies[b].blocks.size()); ++i)
      proxies_.push_back({b, i});
  }
}

void BroadPhase::update(const Model& model, const State& state, const std::vector<Real>& reach,
                        const BodySubset* subset) {
  if (subset && subset->empty()) subset = nullptr;
  if (subset) {
    build_proxies(model, subset);  // the resident bodies change from step to step
    built_for_subset_ = true;
  } else {
    size_t block_count = 0;
    for (const Body& body : model.bodies) block_count += body.blocks.size();
    if (built_for_subset_ || proxies_.size() != block_count ||
        population_version_ != model.population_version)
      build_proxies(model, nullptr);
    population_version_ = model.population_version;
    built_for_subset_ = false;
  }

  const size_t n = proxies_.size();
  poses_.resize(n);
  bounds_.resize(n);
  // Each block's pose and bounds on its own: shared among threads, the same at any count.
  parallel_for(static_cast<long long>(n), 256, [&](long long i) {
    const BlockProxy& p = proxies_[i];
    const BlockInstance& instance = model.bodies[p.body].blocks[p.instance];
    poses_[i] = block_pose(instance, state.bodies[p.body]);
    bounds_[i] = block_bounds(model.blocks[instance.block], poses_[i]);
    if (!reach.empty()) {
      bounds_[i].min.array() -= reach[p.body];
      bounds_[i].max.array() += reach[p.body];
    }
  });
  find_block_pairs(model);
  find_wall_pairs(model, reach, state.time);
  if (subset) keep_owned_pairs(*subset);
}

// Each process tests the pairs that touch a body it owns; a pair of two ghosts is another
// process's (it owns at least one of the two bodies).
void BroadPhase::keep_owned_pairs(const BodySubset& subset) {
  std::erase_if(block_pairs_, [&](const BlockPair& p) {
    if (subset.solved_once) return !subset.owned[proxies_[p.a].body];  // body A: proxy a's
    return !subset.owned[proxies_[p.a].body] && !subset.owned[proxies_[p.b].body];
  });
  std::erase_if(wall_pairs_,
                [&](const WallPair& p) { return !subset.owned[proxies_[p.proxy].body]; });
}

void BroadPhase::drop_resting_pairs(const std::vector<char>& moving) {
  std::erase_if(block_pairs_, [&](const BlockPair& p) {
    return !moving[proxies_[p.a].body] && !moving[proxies_[p.b].body];
  });
  std::erase_if(wall_pairs_, [&](const WallPair& p) { return !moving[proxies_[p.proxy].body]; });
}

void BroadPhase::find_block_pairs(const Model& model) {
  block_pairs_.clear();
  large_.clear();
  entries_.clear();
  const int n = static_cast<int>(proxies_.size());
  if (n < 2) return;

  // The cell: the median largest extent of a block, grown if the scene would need more cells
  // along an axis than a key holds.
  extents_.resize(n);
  Vec3 lo = bounds_[0].min, hi = bounds_[0].max;
  for (int i = 0; i < n; ++i) {
    extents_[i] = (bounds_[i].max - bounds_[i].min).maxCoeff();
    lo = lo.cwiseMin(bounds_[i].min);
    hi = hi.cwiseMax(bounds_[i].max);
  }
  std::nth_element(extents_.begin(), extents_.begin() + n / 2, extents_.end());
  cell_ = std::max(extents_[n / 2], (hi - lo).maxCoeff() / kMaxCellsPerAxis);
  const Real inv_cell = 1 / cell_;
  auto cell_of = [&](const Vec3& p) {
    return Eigen::Matrix<long long, 3, 1>(
        static_cast<long long>(std::floor((p.x() - lo.x()) * inv_cell)),
        static_cast<long long>(std::floor((p.y() - lo.y()) * inv_cell)),
        static_cast<long long>(std::floor((p.z() - lo.z()) * inv_cell)));
  };

  // Every block into the cells its bounds cover; too large a block onto the large list.
  low_cell_.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto c0 = cell_of(bounds_[i].min), c1 = cell_of(bounds_[i].max);
    low_cell_[i] = c0;
    const auto span = (c1 - c0).array() + 1;
    if (span.prod() > kMaxCellsPerBlock) {
      large_.push_back(i);
      continue;
    }
    for (long long z = c0.z(); z <= c1.z(); ++z)
      for (long long y = c0.y(); y <= c1.y(); ++y)
        for (long long x = c0.x(); x <= c1.x(); ++x) entries_.push_back({cell_key(x, y, z), i});
  }
  group_by_cell();

  auto may_touch = [&](int i, int j) {
    const BlockProxy &p = proxies_[i], &q = proxies_[j];
    if (p.body == q.body) return false;
    if (model.bodies[p.body].driven() && model.bodies[q.body].driven()) return false;
    return bounds_[i].overlaps(bounds_[j]);
  };
  // Pairs within each cell, each counted only in the cell of its intersection's lower corner.
  for (size_t first = 0; first < entries_.size();) {
    size_t last = first;
    while (last < entries_.size() && entries_[last].cell == entries_[first].cell) ++last;
    for (size_t s = first; s < last; ++s)
      for (size_t t = s + 1; t < last; ++t) {
        const int i = entries_[s].proxy, j = entries_[t].proxy;
        if (!may_touch(i, j)) continue;
        // The cell of the bounds' intersection's lower corner: as the cell of a coordinate
        // never falls when the coordinate grows, it is the larger of the two blocks' lower
        // cells, axis by axis.
        const auto c = low_cell_[i].cwiseMax(low_cell_[j]);
        if (cell_key(c.x(), c.y(), c.z()) != entries_[first].cell) continue;
        block_pairs_.push_back({i, j});  // i < j: a cell's entries are in proxy order
      }
    first = last;
  }
  // Large blocks against every other block (once for two large ones).
  std::vector<char>& is_large = is_large_;
  is_large.assign(static_cast<size_t>(n), 0);
  for (int i : large_) is_large[i] = 1;
  for (int l : large_)
    for (int j = 0; j < n; ++j) {
      if (j == l || (is_large[j] && j < l) || !may_touch(l, j)) continue;
      block_pairs_.push_back({std::min(l, j), std::max(l, j)});
    }
  sort_block_pairs();
}

// Entries were made in proxy order; a counting sort on the cell (numbered as first met, through
// an open-addressing table) keeps that order within each cell, where a comparison sort of all
// entries cost O(E log E). The cells' own order does not matter: the pairs are sorted after.
void BroadPhase::group_by_cell() {
  const size_t count = entries_.size();
  size_t capacity = 16;
  while (capacity < 2 * count) capacity *= 2;
  constexpr unsigned long long kEmpty = ~0ull;  // keys use 3 * kCellBits = 63 bits
  table_keys_.assign(capacity, kEmpty);
  table_group_.resize(capacity);
  group_of_.resize(count);
  group_start_.clear();
  const size_t mask = capacity - 1;
  for (size_t e = 0; e < count; ++e) {
    const unsigned long long key = entries_[e].cell;
    size_t slot = static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
    while (table_keys_[slot] != kEmpty && table_keys_[slot] != key) slot = (slot + 1) & mask;
    if (table_keys_[slot] == kEmpty) {
      table_keys_[slot] = key;
      table_group_[slot] = static_cast<int>(group_start_.size());
      group_start_.push_back(0);
    }
    group_of_[e] = table_group_[slot];
    ++group_start_[group_of_[e]];
  }
  int next = 0;
  for (int& start : group_start_) next += std::exchange(start, next);
  grouped_.resize(count);
  for (size_t e = 0; e < count; ++e) grouped_[group_start_[group_of_[e]]++] = entries_[e];
  entries_.swap(grouped_);
}

// Pairs in (a, b) order, so that the narrow phase sees the same order whatever the grid: a
// counting sort on a, then each a's few partners sorted.
void BroadPhase::sort_block_pairs() {
  const size_t n = proxies_.size();
  pair_start_.assign(n + 1, 0);
  for (const BlockPair& p : block_pairs_) ++pair_start_[p.a + 1];
  for (size_t i = 0; i < n; ++i) pair_start_[i + 1] += pair_start_[i];
  sorted_pairs_.resize(block_pairs_.size());
  pair_next_.assign(pair_start_.begin(), pair_start_.end() - 1);
  for (const BlockPair& p : block_pairs_) sorted_pairs_[pair_next_[p.a]++] = p;
  for (size_t i = 0; i < n; ++i)
    std::sort(sorted_pairs_.begin() + pair_start_[i], sorted_pairs_.begin() + pair_start_[i + 1],
              [](const BlockPair& p, const BlockPair& q) { return p.b < q.b; });
  block_pairs_.swap(sorted_pairs_);
}

void BroadPhase::find_wall_pairs(const Model& model, const std::vector<Real>& reach, Real time) {
  wall_pairs_.clear();
  for (int i = 0; i < static_cast<int>(proxies_.size()); ++i) {
    if (model.bodies[proxies_[i].body].driven()) continue;
    const Vec3 centre = (bounds_[i].min + bounds_[i].max) / 2;
    const Vec3 half = (bounds_[i].max - bounds_[i].min) / 2;
    const Real extra = reach.empty() ? 0 : reach[proxies_[i].body];  // bounds grew by one reach
    for (int w = 0; w < static_cast<int>(model.walls.size()); ++w) {
      const Wall& wall = model.walls[w];
      if (!(time < wall.removed_at)) continue;  // gone (a gate opened)
      // The lowest corner of the bounds along the wall's normal: behind the plane or not.
      if (wall.normal.dot(centre - wall.point) - wall.normal.cwiseAbs().dot(half) < extra)
        wall_pairs_.push_back({i, w});
    }
  }
}

}  // namespace tem
