// The approximate cutter's tree of cells (approximate_decomposition.cpp describes the method,
// approximate_cuts.hpp the cut of one part): its growth cut by cut, the improvement pass that
// trades a merge for a better cut, the last cuts chosen again (cut_tree.cpp) and its planes
// moved (cut_tree_refine.cpp). A node is a leaf while it has no children; leaves keep their
// best cut once found. Internal to src/mesh.
#pragma once

#include <optional>
#include <vector>

#include "mesh/approximate_cuts.hpp"

namespace tem::approximate {

class CutTree {
 public:
  // One leaf, the whole solid. At most max_blocks leaves; a leaf whose concavity is below
  // `enough` is not cut for it, a leaf whose block strays further than distance_goal outside
  // the mesh is cut first; blocks within `touching` of each other are neighbours; a plane is
  // moved only where that lowers the hulls by more than smallest_gain.
  CutTree(Leaf root, const Context& context, int max_blocks, Real enough, Real distance_goal,
          Real touching, Real smallest_gain);

  // A solid of several shells whose hulls are apart (pieces of at least smallest_volume)
  // starts as a leaf for each, when max_blocks allows.
  void start_with_shells(Real smallest_volume);
  // Cuts while blocks are left, up to `up_to` leaves (max_blocks if -1): a block that strays
  // too far outside first, then concavity.
  void grow(int up_to = -1);
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
  // Moves the planes of the tree, root first, each shifted or turned with every plane below it
  // kept, while that lowers the sum of the hulls' volumes below it and strays no farther
  // outside the mesh (by the blocks' sampled distance): the growth chose each plane for the
  // cuts it foresaw, not for the ones that came. Planes above a block merged from two
  // neighbours stay, and so do those of the largest parts (cut_tree_refine.cpp). True if some
  // plane moved.
  bool refine_planes();
  // The leaves, taken out of the tree.
  std::vector<Leaf> take_leaves();

 private:
  struct Node {
    Leaf leaf;
    int parent = -1;
    std::vector<int> children;
    std::optional<CutPlane> plane;  // the plane that cut it, if one did
    int first_side_pieces = 0;      // its first children, the pieces of the plane's first side
    std::optional<Split> next;
    bool next_known = false;
    bool alive = true;
    bool unsettled = false;  // a plane above it moved: its distance (and block) to be found
    // Something below it changed since its plane last found no move (refine_planes).
    bool moved_below = true;
    bool is_leaf() const { return alive && children.empty(); }
  };
  struct LeafPair {
    int a, b;
    Real cost = 0;
    bool refused = false;  // merged_leaf said no; not asked again
  };

  // Leaf n's best cut, with at most `room` children (found again if the one known has more).
  std::optional<Split>& known_split(int n, int room);
  // Marks n and the nodes above it as changed below (Node::moved_below).
  void touched(int n);
  // Replaces leaf n by its children (the cut found in `cut`).
  void apply(int n, Split cut);
  // The cheapest pair merge that costs less than `below` (index into leaf_pairs_, or -1), and
  // its leaf. Pairs are listed as leaves appear; siblings are left to the merge into their node.
  int cheapest_pair_merge(Real below, std::optional<Leaf>& merged);

  // Whether every node below n (n too) is cut by a plane or is a leaf of the tree that may be
  // cut again (not merged with a neighbour): the nodes whose parts a moved plane can find again.
  bool plain_below(int n) const;
  // The parts of n's children when n's part is `part` and its plane `plane`, the pieces of each
  // side in the order split made them; nothing if a side is under kSmallestSide of the part or
  // falls into another number of pieces. Parts that will be cut again keep their surface
  // (cut_part), the others only if keep_surface.
  std::optional<std::vector<MeshPart>> child_parts(int n, const MeshPart& part,
                                                   const CutPlane& plane, bool keep_surface) const;
  // The leaves below n (n itself if a leaf).
  std::vector<int> leaves_below(int n) const;
  // Finds the distance of a node whose part changed when a plane above it moved, and its block
  // too if it is not a leaf.
  void settle(int n);
  // Whether `part`, cut anew, is the part node n holds, so that its hull and all below it stay
  // as they are (a hull depends on the points alone; a part cut further on its surface too).
  bool holds(int n, const MeshPart& part) const;
  // The sum of the hulls' volumes of the leaves below n when n's part is `part` and its plane
  // `plane`, every plane below kept; nothing if a cut leaves a side under kSmallestSide.
  std::optional<Real> hulls_below(int n, const MeshPart& part, const CutPlane& plane) const;
  // The nodes below n whose parts change when n's part is `part` and its plane `plane`, with
  // their leaves so made, or nothing if some leaf's hull is no valid block.
  std::optional<std::vector<std::pair<int, Leaf>>> rebuilt_below(int n, const MeshPart& part,
                                                                 const CutPlane& plane) const;
  // Moves node n's plane once, by the candidate that lowers the hulls below it most and whose
  // blocks are valid, stray no farther and reach into no merged block. True if it moved.
  bool move_plane(int n);

  std::vector<Node> nodes_;
  int leaf_count_ = 1;
  Context context_;
  int max_blocks_;
  Real enough_, distance_goal_, touching_, smallest_gain_;
  std::vector<LeafPair> leaf_pairs_;
  size_t paired_ = 0;  // the pairs of nodes below this index are listed
};

}  // namespace tem::approximate
