// A contact patch: one place where two bodies (or a body and a wall) overlap (method.md §5).
#pragma once

#include <tuple>
#include <vector>

#include "collision/block_manifold.hpp"
#include "tem/types.hpp"

namespace tem {

struct ContactPatch {
  int body_a = -1;
  int body_b = -1;   // -1 when the other side is a wall
  int wall = -1;     // index into Model::walls, or -1
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, from A into B: the force on A acts along -normal
  Real depth = 0;               // overlap along the normal, > 0
  int features = 0;             // flagged nodes and edges that made it
  // Points of the overlap: nodes inside the other side and edge-face intersections. In the
  // default variant these are the corners of the overlap region (polygon edges only).
  std::vector<Vec3> vertices;
  Vec3 bounds_min = Vec3::Zero(), bounds_max = Vec3::Zero();  // of the vertices
  // A patch of contact before overlap (block_manifold.hpp) has no vertices but at most four
  // points, each with its own gap; its depth is then minus the smallest gap (< 0: still apart).
  // count 0 for a patch of overlap features.
  Manifold manifold;
  // With contact before overlap: the block instances (indices into Model::bodies[body].blocks)
  // whose pair made the patch, from which a sub-step rebuilds it (refreshed_patches.hpp); -1
  // for a wall's side.
  int block_a = -1, block_b = -1;
  // Of a block pair with contact before overlap: B's block frame in A's at the separating-axis
  // search that found the manifold's features (this step's, or the one the pair cache took them
  // from: pair_cache.hpp).
  Mat3 searched_rotation = Mat3::Identity();
  Vec3 searched_offset = Vec3::Zero();
  // And the manifold's node past the rim at that search (Manifold::beyond_rim).
  Real searched_beyond_rim = 0;
};

// The patch of a manifold of contact before overlap: its points' mean, minus its smallest gap as
// depth, the bounds of its points (bodies, walls and blocks are the caller's to set).
ContactPatch manifold_patch(const Manifold& m);

// The order of a step's patches (detect_contacts.cpp sorts them so) and of everything made from
// them: points, friction, penalty springs, contact memory gathered over ranks. By body A, body
// pairs before wall pairs, then by body B or wall.
template <class Contact>
std::tuple<int, bool, int> pair_key(const Contact& c) {
  const bool wall = c.wall >= 0;
  return {c.body_a, wall, wall ? c.wall : c.body_b};
}

}  // namespace tem
