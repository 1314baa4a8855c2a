// The contact memory the next step starts from (ContactForces: the last step's points, their
// normal impulses and the patches' friction for SEMM's warm start; the penalty springs), in
// pieces that travel with their body A between ranks and gather into one process's order.
#pragma once

#include <vector>

#include "distributed/messages.hpp"
#include "forces/contact_forces.hpp"

namespace tem::distributed {

// One patch of SEMM memory: its friction and its points with their impulses.
struct MemoryPatch {
  PatchFriction friction;
  std::vector<ContactPoint> points;
  std::vector<PointImpulse> impulses;
};

// The SEMM memory of `forces` as patches, in its order.
std::vector<MemoryPatch> memory_patches(const ContactForces& forces);
// Lays `patches` back into `forces`, stably sorted into one process's order (by body A, body
// pairs before walls, then body B or wall), points and friction renumbered.
void set_memory_patches(std::vector<MemoryPatch> patches, ContactForces& forces);

void pack(Packer& out, const MemoryPatch& p);
MemoryPatch unpack_memory_patch(Unpacker& in);

// Stable sort of springs into one process's order.
void sort_springs(std::vector<PenaltySpring>& springs);

}  // namespace tem::distributed
