// The patches of one detection rebuilt at every sub-step of a step (contact.substeps).
//
// Detection has two parts of very different cost: finding which features of two blocks face
// each other (the separating-axis search over faces and edge pairs: most of a step's narrow
// phase) and, given those features, the points between them (a clip of two faces, or the
// closest points of two edges). With contact before overlap the search already covers the whole
// step: its margin holds everything the bodies can reach in it (contact_margins.hpp). A sub-step
// therefore keeps the step's block pairs and the features found for them and only places the
// two blocks again and redoes the clip or the closest points, as Box3D's soft step and Jolt's
// contact cache rebuild a manifold from cached features. The normal turns with the reference
// face (or the edge pair), and the points and gaps are the true ones at the sub-step's poses:
// a coin that rocks brings the corner that was out of the four kept points back in, which
// carrying the detected points with the bodies cannot (the points it dropped stay dropped).
#pragma once

#include <array>
#include <vector>

#include "collision/block_manifold.hpp"
#include "contact/contact_patch.hpp"
#include "contact/detect_contacts.hpp"
#include "world/model.hpp"

namespace tem {

// Reused memory: one manifold scratch per thread, the blocks placed for the sub-step (`world`,
// for `placed`'s body and instance; `slot`: each block's place there, by `first_block` of its
// body, or -1), and whether each detected patch was found again.
struct RefreshScratch {
  std::vector<ManifoldScratch> threads;
  std::vector<WorldBlock> world;
  std::vector<std::array<int, 2>> placed;
  std::vector<int> first_block, slot;
  std::vector<char> found;
};

// `out`: the patches of `detected` (contact before overlap, from find_patches) rebuilt at
// `state` within the step's margins (contact.reach), in the same order; a pair with nothing
// left within its margin is left out. The same result with any number of threads.
void refresh_patches(const Model& model, const State& state, const ContactWorkspace& contact,
                     const std::vector<ContactPatch>& detected, RefreshScratch& scratch,
                     std::vector<ContactPatch>& out);

}  // namespace tem
