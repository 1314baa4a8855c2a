// Contact before overlap: the signed gap of two convex blocks (or of a block and a wall) and a
// patch of at most four points where they touch or are about to, each with its own gap.
//
// Why: the paper's tests (node in element, edge through face) see a contact only once the
// blocks overlap, so a body arriving at speed v sinks about v dt before the solver acts, and a
// pile is right only at tiny time steps. A point that is still a gap s > 0 apart can instead be
// handed to the solver with the condition that the gap not close past zero within the step
// (normal relative velocity after the step >= -s/dt), which pushes nothing unless the bodies
// would otherwise overlap (speculative contact: Box2D, Box3D, Jolt, Chrono's envelope).
//
// How: separating axes. For two convex polyhedra the largest separation along the candidate
// axes (each block's face normals, and the cross products of an edge of each that build a face
// of their Minkowski difference, the Gauss-map arc test of Gregorius) is the gap where the
// nearest features are a face and anything, or two edges, and a lower bound of it otherwise;
// negative, it is the depth of the shallowest way out. A face axis makes that face the
// reference: the most opposed face of the other block (the incident face) is clipped by the
// reference face's side planes (Sutherland-Hodgman) and each clipped corner within the margin is
// a point, its gap its height over the reference plane. An edge axis gives one point, between
// the two edges' closest points. The patch keeps the deepest point and the three that span the
// largest area with it, so a face resting on a face stands on four corners.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "collision/block_pose.hpp"
#include "geometry/block.hpp"

namespace tem {

inline constexpr int kManifoldPoints = 4;

// Which features made a manifold: the pair of edges whose cross product is its normal, the
// reference face of A or of B that the other block's incident face was clipped against, or a
// wall. A sub-step rebuilds the manifold from them at the bodies' new poses without searching
// the axes again (rebuild_manifold, refreshed_patches.hpp). `edges_past_rim` is an edge pair's
// point taken where a preferred face's clip came out empty: its gap is bounded by that face's
// separation too, which the edges alone do not give back, so it is rebuilt by the whole search
// and never kept in the pair cache (the cache then answers exactly as the search would).
enum class ManifoldFeature : std::uint8_t { none, edges, face_of_a, face_of_b, wall,
                                            edges_past_rim };

struct Manifold {
  Vec3 normal = Vec3::UnitZ();  // unit, from A into B (the force on A acts along -normal)
  int count = 0;
  std::array<Vec3, kManifoldPoints> point = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                             Vec3::Zero()};  // world, midway between surfaces
  std::array<Real, kManifoldPoints> gap{};    // > 0 apart, < 0 overlapping
  ManifoldFeature feature = ManifoldFeature::none;
  // The edges (indices into WorldBlock's edge lists) or the reference face (a polygon index of
  // its block; the other -1).
  int feature_a = -1, feature_b = -1;
  // A face manifold's node past the rim: how much deeper below the reference plane the other
  // block's deepest node lies than the deepest kept corner (0 where that node is one of them).
  // Such a node is beside the reference face, not on it (a coin lying across another's rim,
  // tilted). A sub-step rebuilding the manifold lets it lie as deep again before it calls the
  // search (rebuild_from_features).
  Real beyond_rim = 0;
};

// A block placed in the world for one step: what every pair it is in reads, computed once.
struct WorldBlock {
  Vec3 centre = Vec3::Zero();  // the block's centroid
  std::vector<Vec3> nodes;     // world
  std::vector<Vec3> normals;   // world outward polygon normals
  std::vector<Real> offsets;   // world planes: normal . x = offset
  // The edges between two polygons (not the diagonals inside one): end node, direction, the
  // normals n1, n2 of the two polygons and n2 x n1 (the Gauss-map arc of the edge).
  std::vector<int> edge_node;
  std::vector<Vec3> edge_direction, edge_n1, edge_n2, edge_arc;
};

void place_block(const Block& block, const BlockPose& pose, WorldBlock& out);
// place_block in two parts: the centre, nodes and face planes, all that a face's clip or a wall
// reads, then the edges, which only the axis search reads (from the placed nodes and normals).
// A sub-step rebuilding a face patch needs no edges unless the search must answer
// (rebuild_from_features).
void place_faces(const Block& block, const BlockPose& pose, WorldBlock& out);
void place_edges(const Block& block, WorldBlock& out);

// Reused memory of one thread, on cache lines of its own (threads' scratch lies side by side in
// a vector, and every clip writes its vectors' ends).
struct alignas(64) ManifoldScratch {
  WorldBlock a, b;  // for the overloads that take poses
  std::vector<Vec3> clip_in, clip_out;
  std::vector<Real> clip_distance;  // each clip_in point's distance out of the side clipped by
  std::vector<Vec3> candidates;  // points within the margin, before reduce_points
  std::vector<Real> candidate_gaps;
  std::vector<int> edge_list;  // B's edges that may face A
};

// A face of A or of B whose plane keeps the other block's nodes farther out than a margin.
struct SeparatingFace {
  ManifoldFeature side = ManifoldFeature::none;  // face_of_a, face_of_b, or none
  int face = -1;
};

// The patch of two convex blocks whose gap is below `margin` (false, and count 0, otherwise).
// `separated` (if given): the face axis that put them beyond the margin, where one did.
bool block_manifold(const Block& a, const WorldBlock& world_a, const Block& b,
                    const WorldBlock& world_b, Real margin, ManifoldScratch& scratch,
                    Manifold& out, SeparatingFace* separated = nullptr);

// Whether `face` still keeps the blocks farther apart than `margin`, by the very arithmetic of
// block_manifold's face test: where it does, block_manifold returns false too, so a caller may
// skip it (a separating-axis cache; contact/pair_cache.hpp). False for a face the blocks lack.
bool still_separated(const WorldBlock& world_a, const WorldBlock& world_b,
                     const SeparatingFace& face, Real margin);
bool block_manifold(const Block& a, const BlockPose& pose_a, const Block& b,
                    const BlockPose& pose_b, Real margin, ManifoldScratch& scratch,
                    Manifold& out);

// The manifold of the features that made `detected` (same edge pair, or same reference face
// with the incident face chosen again), at the blocks' placements `world_a`, `world_b`, within
// `margin`: what the whole search would find while the pair's relative pose has changed too
// little for another axis to win. False, with count 0, when nothing is within the margin.
// `searched` (if given): whether the features no longer held and the whole search answered.
bool rebuild_manifold(const Block& a, const WorldBlock& world_a, const Block& b,
                      const WorldBlock& world_b, Real margin, const Manifold& detected,
                      ManifoldScratch& scratch, Manifold& out, bool* searched = nullptr);

// rebuild_manifold without the search, on blocks placed at least by place_faces: `held` (and
// `out` the manifold), `apart` (nothing within the margin), or `search` where the features no
// longer answer and block_manifold must, on blocks with their edges placed.
enum class Rebuild : std::uint8_t { held, apart, search };
Rebuild rebuild_from_features(const Block& a, const WorldBlock& world_a, const Block& b,
                              const WorldBlock& world_b, Real margin, const Manifold& detected,
                              ManifoldScratch& scratch, Manifold& out);

// The patch of a convex block and a wall plane (normal into the space where bodies live; the
// patch normal is then -wall_normal): the corners of the block's face most opposed to the wall,
// and its deepest node, within `margin` of the plane.
bool wall_manifold(const Block& block, const WorldBlock& world, const Vec3& wall_point,
                   const Vec3& wall_normal, Real margin, ManifoldScratch& scratch, Manifold& out);
bool wall_manifold(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                   const Vec3& wall_normal, Real margin, ManifoldScratch& scratch, Manifold& out);

// Keeps at most four of `count` candidate points: the deepest (among points deeper than the
// least gap plus `equal_depth`, the farthest along `along`, a direction fixed to the face),
// the farthest from it, and the two that add the most area on either side of the line through
// them, each choice the same while the points barely move. Exposed for tests.
int reduce_points(const Vec3& normal, const Vec3& along, Real equal_depth, const Vec3* points,
                  const Real* gaps, int count, std::array<int, kManifoldPoints>& kept);

}  // namespace tem
