// Steps 1-3 of a simulation step (architecture.md): broad phase, narrow phase, patches. From a
// state to the list of contact patches between bodies and between bodies and walls.
#pragma once

#include <vector>

#include "collision/broad_phase.hpp"
#include "collision/narrow_phase.hpp"
#include "contact/contact_patch.hpp"
#include "contact/patches.hpp"
#include "world/model.hpp"

namespace tem {

// The scene's contact.normals: the paper's node/edge-normal rule or the face-based default.
PatchVariant patch_variant(const SceneDef& scene);

// Everything contact detection reuses from one step to the next.
struct ContactWorkspace {
  BroadPhase broad_phase;
  NarrowPhaseScratch narrow;
  PairFeatures pair;
  WallFeatures wall;
  PatchScratch patch;
};

// Narrow phase and patches for the pairs of the workspace's last broad-phase update. Patches
// ordered by body pair (walls after bodies, by wall index), deterministic.
void find_patches(const Model& model, PatchVariant variant, ContactWorkspace& workspace,
                  std::vector<ContactPatch>& patches);

// Broad phase, then find_patches.
void detect_contacts(const Model& model, const State& state, PatchVariant variant,
                     ContactWorkspace& workspace, std::vector<ContactPatch>& patches);

}  // namespace tem
