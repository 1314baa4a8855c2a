// The broad phase (step 1 of a simulation step): from the world bounds of every block to the
// block pairs and block-wall pairs whose bounds overlap, the only ones the narrow phase tests.
//
// Why a uniform grid and not sweep-and-prune. In a pile of N bodies in a box, sorting along one
// axis leaves every block overlapping, along that axis, the whole slab of bodies beside it
// (about N^(2/3) of them), so the sweep costs about N^(5/3). A grid whose cells are about one
// block wide puts a bounded number of blocks in each cell, and the cost is linear in N (the
// (cell, block) entries are grouped by a counting sort, not a comparison sort). The cell is the
// median block extent, so a few large blocks (a floor slab, a column) do not coarsen it; a block
// spanning too many cells goes on a short list that is tested against every block instead.
//
// A pair that shares several cells is reported once: by the cell that holds the lower corner of
// the intersection of the two bounds. Pairs come out sorted, so the narrow phase and everything
// after it see the same order whatever the grid: results do not depend on the cell size.
#pragma once

#include <vector>

#include "collision/block_pose.hpp"
#include "geometry/aabb.hpp"
#include "world/model.hpp"

namespace tem {

// One block instance of one body: what the broad phase sorts.
struct BlockProxy {
  int body;
  int instance;  // index into Model::bodies[body].blocks
};

struct BlockPair {
  int a, b;  // proxy indices, a < b, of blocks of two different bodies
};

struct WallPair {
  int proxy;
  int wall;  // index into Model::walls
};

class BroadPhase {
 public:
  // Poses and world bounds of every block at `state`, then the overlapping pairs. Pairs of two
  // fixed bodies, and fixed bodies against walls, are never reported. With `reach` (one per
  // body, contact_margins.hpp) every block's bounds grow by its body's reach, and a block is
  // paired with a wall when its bounds come within twice its reach of the plane: the pairs
  // that may make contact before overlap.
  //
  // With a `subset` (domain decomposition) only its resident bodies take part, and only pairs
  // with at least one owned body are reported. Proxies keep the bodies' order, so the pairs
  // are those of one process with every body, filtered, in the same order.
  void update(const Model& model, const State& state, const std::vector<Real>& reach = {},
              const BodySubset* subset = nullptr);

  // Drops the pairs in which no body moves this step (`moving`: one flag per body): two bodies
  // asleep, a body asleep and a fixed one, a body asleep and a wall (simulation/sleep.hpp). The
  // pairs left keep their order.
  void drop_resting_pairs(const std::vector<char>& moving);

  const std::vector<BlockProxy>& proxies() const { return proxies_; }
  const std::vector<BlockPose>& poses() const { return poses_; }
  const std::vector<Aabb>& bounds() const { return bounds_; }
  const std::vector<BlockPair>& block_pairs() const { return block_pairs_; }
  const std::vector<WallPair>& wall_pairs() const { return wall_pairs_; }
  // The cell edge of the last update and how many blocks were too large for the grid.
  Real cell_size() const { return cell_; }
  int large_blocks() const { return static_cast<int>(large_.size()); }

 private:
  void build_proxies(const Model& model, const BodySubset* subset);
  void keep_owned_pairs(const BodySubset& subset);
  void find_block_pairs(const Model& model);
  void group_by_cell();
  void sort_block_pairs();
  // Walls taken away (removed_at) by `time` take no part.
  void find_wall_pairs(const Model& model, const std::vector<Real>& reach, Real time);

  std::vector<BlockProxy> proxies_;
  std::vector<BlockPose> poses_;
  std::vector<Aabb> bounds_;
  std::vector<BlockPair> block_pairs_;
  std::vector<WallPair> wall_pairs_;
  // Grid scratch, reused between steps.
  struct Entry {
    unsigned long long cell;
    int proxy;
  };
  std::vector<Entry> entries_, grouped_;
  std::vector<unsigned long long> table_keys_;  // cell keys of an open-addressing table
  std::vector<int> table_group_, group_of_, group_start_;
  std::vector<int> pair_start_, pair_next_;
  std::vector<BlockPair> sorted_pairs_;
  std::vector<Eigen::Matrix<long long, 3, 1>> low_cell_;  // per proxy: its bounds' lowest cell
  std::vector<int> large_;
  std::vector<char> is_large_;  // per proxy, kept between steps
  bool built_for_subset_ = false;
  long long population_version_ = -1;  // Model::population_version the proxies were built for
  std::vector<Real> extents_;
  Real cell_ = 0;
};

// World bounds of a block's nodes at a pose (exact for the polyhedron).
Aabb block_bounds(const Block& block, const BlockPose& pose);

}  // namespace tem
