// Volume, centre of mass and inertia from tetrahedral elements (§2.4 of the paper, eqs. 4-7).
//
// Erratum of eq. 7 (method.md §2): as printed it adds M^c t_j t_k to *inertia tensors*, which is
// the parallel-axis rule of *second moments*. Here blocks are combined as second moments
// S = integral of rho x x^T, and eq. 4 turns the sum into an inertia tensor once, at the end.
#pragma once

#include <vector>

#include "geometry/block.hpp"
#include "tem/types.hpp"

namespace tem {

struct MassProperties {
  Real volume = 0;
  Real mass = 0;
  Vec3 center = Vec3::Zero();         // centre of mass
  Mat3 second_moment = Mat3::Zero();  // integral of rho (x-c)(x-c)^T dV
};

// Eq. 4: A_jk = I_ii delta_jk - I_jk.
inline Mat3 inertia_from_second_moment(const Mat3& s) { return s.trace() * Mat3::Identity() - s; }

// A block's properties in its own frame (centre at the origin): eqs. 5-6 summed over elements.
MassProperties block_mass_properties(const Block& block, Real density);

// A part placed in a common frame: x = rotation * x_part + position.
struct PlacedMass {
  MassProperties mass;
  Mat3 rotation;
  Vec3 position;
};

// Eq. 7, corrected: S = sum_c (B^c S^c B^cT + M^c t^c t^cT), t^c from the combined centre.
MassProperties combine(const std::vector<PlacedMass>& parts);

}  // namespace tem
