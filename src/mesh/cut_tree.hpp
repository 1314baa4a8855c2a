// The approximate cutter's tree of cells (approximate_decomposition.cpp describes the method,
// approximate_cuts.hpp the cut of one part): its growth cut by cut, the improvement pass that
// trades a merge for a better cut, and the last cuts chosen again. A node is a leaf while it
// has no children; leaves keep their best cut once found. Internal to src/mesh.
#pragma once

#include <optional>
#include <vector>

#include "mesh/approximate_cuts.hpp"

namespace tem::approximate {

class CutTree {
 public:
  // One leaf, the whole solid. At most max_blocks leaves; a leaf whose concavity is below
  // `enough` is not cut for it, a leaf whose block strays further than distance_goal outside
  // the mesh is cut first; blocks within `touching` of each other are neighbours.
  CutTree(Leaf root, const Context& context, int max_blocks, Real enough, Real distance_goal,
          Real touching);

  // A solid of several shells whose hulls are apart (pieces of at least smallest_volume)
  // starts as a leaf for each, when max_blocks allows.
  void start_with_shells(Real smallest_volume);
  // Cuts while blocks are left: a block that strays too far outside first, then concavity.
  void grow();
  // Merges the leaves whose joint block adds least over theirs and spends the blocks freed on
  // the leaf whose cut gains more, while that lowers the sum of the hulls' volumes (so it ends);
  // blocks still left go to further cuts. Two kinds of merge: a node's children back into it,
  // and two neighbouring leaves of different nodes into a block of their joint hull (a node of
  // its own, outside the tree), where that hull reaches into no other block.
  void improve();
  // The last cuts again, without the look ahead: a node whose two children stay leaves gains
  // nothing from a cut that prepares further cuts, so it is cut anew by the plane whose two
  // hulls are least, where that lowers them and strays no farther outside the mesh. From here
  // on every cut is chosen so. True if some cell changed.
  bool recut_last_cuts();
  // The leaves, taken out of the tree.
  std::vector<Leaf> take_leaves();

 private:
  struct Node {
    Leaf leaf;
    int parent = -1;
    std::vector<int> children;
    std::optional<Split> next;
    bool next_known = false;
    bool alive = true;
    bool is_leaf() const { return alive && children.empty(); }
  };
  struct LeafPair {
    int a, b;
    Real cost = 0;
    bool refused = false;  // merged_leaf said no; not asked again
  };

  // Leaf n's best cut, with at most `room` children (found again if the one known has more).
  std::optional<Split>& known_split(int n, int room);
  // Replaces leaf n by its children (the cut found in `cut`).
  void apply(int n, Split cut);
  // The cheapest pair merge that costs less than `below` (index into leaf_pairs_, or -1), and
  // its leaf. Pairs are listed as leaves appear; siblings are left to the merge into their node.
  int cheapest_pair_merge(Real below, std::optional<Leaf>& merged);

  std::vector<Node> nodes_;
  int leaf_count_ = 1;
  Context context_;
  int max_blocks_;
  Real enough_, distance_goal_, touching_;
  std::vector<LeafPair> leaf_pairs_;
  size_t paired_ = 0;  // the pairs of nodes below this index are listed
};

}  // namespace tem::approximate
