// Cutting one part of a mesh's solid, for the approximate cutter (approximate_decomposition.cpp
// describes the method; cut_tree.hpp keeps the tree): a part and its block as a leaf of the tree,
// the best plane to cut a leaf by, and the block of two neighbouring leaves merged. Internal to
// src/mesh.
#pragma once

#include <optional>
#include <vector>

#include "geometry/block.hpp"
#include "mesh/mesh_distance.hpp"
#include "mesh/plane_cut.hpp"

namespace tem::approximate {

// A part whose hull exceeds it by less than this fraction of the mesh's volume is left whole:
// at the scene default of 32 blocks such parts add 1.6 % of the mesh's volume at most.
inline constexpr Real kConcavityFraction = 5e-4;
// A cut must leave at least this fraction of the part's volume on each side: no slivers.
inline constexpr Real kSmallestSide = 1e-3;
// What the look ahead saves counts for a little less than the same saving now: it is an
// estimate, and a cut that gains now is preferred to one that only prepares a gain.
inline constexpr Real kLookaheadWeight = 0.9;
// Hull vertices closer than this fraction of the part's size are welded (hull_block).
inline constexpr Real kWeld = 1e-5;
// A block that strays further than this fraction of the mesh's bounding-box diagonal outside
// the mesh is cut first, by the plane whose sides stray least (the goal is 2 %, less a margin
// for the sampled estimate that ranks the planes).
inline constexpr Real kDistanceGoal = 0.015;
// A plane of the tree is moved (CutTree::refine_planes) only where that lowers the sum of the
// hulls' volumes by more than this fraction of the mesh's volume: smaller moves cost their time
// and change the blocks by less than the last digit of the figures reported.
inline constexpr Real kSmallestMoveGain = 1e-5;
// The planes are first moved when the tree has this many leaves, then each time they double.
inline constexpr int kFirstPlaneMoves = 8;
// The Hausdorff distance is found to within this fraction of the mesh's bounding-box diagonal
// (an eighth of the 2 % that kDistanceGoal aims under).
inline constexpr Real kDistancePrecision = 2.5e-3;

struct Leaf {
  MeshPart part;
  PolyhedronDef block;
  Real hull_volume = 0;
  Real distance = 0;   // how far its block strays outside the mesh (largest_outside_distance)
  bool final = false;   // not to be cut: no candidate plane gave two valid blocks, or merged
  bool merged = false;  // two neighbours' hull (merged_leaf): not cut, though a cut may exist
  Real concavity() const { return hull_volume - part.volume; }
};

// A leaf's best cut: its children, and what it gains (its hull's volume less the children's).
// A side that the cut leaves in pieces whose hulls are apart gives a child per piece.
struct Split {
  std::vector<Leaf> children;
  Real gain = 0;
  // The plane that made it, if one did; its first first_side_pieces children are the pieces of
  // the side below the plane (the first side of cut_part), the rest those of the other side.
  std::optional<CutPlane> plane;
  int first_side_pieces = 0;
};

// The split of a leaf whose hull's volume is `hull` into these children.
Split split_into(Real hull, std::vector<Leaf> children);

// What the cutter needs beside the part: the mesh's distance field, for cutting by distance.
struct Context {
  const MeshDistance* distance;
  int room;           // the most children a split may have (the blocks left, plus one)
  Real precision;     // of distances, and the tie between two of them
  Real tie;           // between two volumes
  bool for_distance;  // this split aims at the distance of the part's block outside the mesh
  // What the look ahead's saving counts for in a candidate's score: kLookaheadWeight while the
  // tree grows, 0 for a last cut whose sides stay blocks.
  Real lookahead = kLookaheadWeight;
};

// A leaf for each part, or nothing if some part's hull is no valid block.
std::optional<std::vector<Leaf>> leaves_of(std::vector<MeshPart> parts, const Context& context);

// The leaf's children by the best candidate plane whose sides make valid blocks: a child for
// each side, or for each of a side's pieces whose hulls are apart when there is room for them.
std::optional<Split> split(const Leaf& leaf, Context context);

// What the hull of two leaves' blocks together adds over their own hulls.
Real merge_cost(const Leaf& a, const Leaf& b);

// Whether the block reaches into one of the others' blocks (touching within eps is apart).
bool reaches_into(const PolyhedronDef& block, const std::vector<const Leaf*>& others, Real eps);

// The leaf of a and b merged, if its hull makes a valid block that reaches into none of
// `others` (blocks never overlap) and strays no farther outside the mesh than the goal or the
// worse of the two did. Its part keeps only the corners, which is all a hull needs: a merged
// leaf is not cut again (`final`).
std::optional<Leaf> merged_leaf(const Leaf& a, const Leaf& b,
                                const std::vector<const Leaf*>& others, Real distance_goal,
                                Real eps, const Context& context);

}  // namespace tem::approximate
