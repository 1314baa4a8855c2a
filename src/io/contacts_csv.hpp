// contacts.csv (interface.md): one row per contact patch per output time, with the patch point,
// its unit normal from body_a into body_b, its depth, and the contact force's normal and
// tangential magnitudes on body_a over the step (0 where no forces were computed).
#pragma once

#include <ostream>
#include <vector>

#include "contact/contact_patch.hpp"
#include "forces/contact_forces.hpp"
#include "world/model.hpp"

namespace tem {

inline constexpr const char* kContactsCsvHeader =
    "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,fn,ft";

// Writes the rows of one time. `forces` is empty or has one entry per patch. A wall is named
// `wall`. Numbers are written with the shortest digits that read back exactly.
void write_contact_rows(std::ostream& out, const Model& model, Real time,
                        const std::vector<ContactPatch>& patches,
                        const std::vector<PatchForce>& forces = {});

}  // namespace tem
