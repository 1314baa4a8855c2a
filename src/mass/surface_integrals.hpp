// An independent route to mass properties, used to check the element sums of eqs. 4-7: the
// divergence theorem turns the volume integrals of 1, x, x^2 and xy over a closed polyhedron into
// sums over its surface triangles of polynomials in the vertex coordinates (D. Eberly,
// "Polyhedral Mass Properties (Revisited)", 2002). It uses no interior point and no
// tetrahedron, so it shares nothing with the element formula but the surface itself.
#pragma once

#include <array>
#include <vector>

#include "mass/mass_properties.hpp"

namespace tem {

// Unit-density volume, centroid and second moment about the centroid of the solid bounded by
// outward-oriented (counter-clockwise seen from outside) triangles.
MassProperties surface_mass_properties(const std::vector<std::array<Vec3, 3>>& triangles);

}  // namespace tem
