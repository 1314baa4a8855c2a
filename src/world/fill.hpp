// Particle insertion (scene key `fill`): N copies of a template body at random positions and
// orientations in a region, none overlapping, reproducible from a seed.
//
// Why bounding spheres: a copy is accepted when its bounding sphere (centre of mass, body_size)
// meets no other body's and stays inside the region. That guarantees no initial overlap for any
// shape, orientation and neighbour, at the price of a looser packing than shape-aware tests
// would allow (random sequential addition of spheres jams near 38% of the region's volume).
// Bodies then settle under gravity, as DEM users fill a box: poured, not packed.
//
// Reproducible: the generator is std::mt19937_64 (its sequence is fixed by the C++ standard)
// with our own conversion to [0, 1) (std::uniform_real_distribution is not specified exactly),
// so the same seed gives the same bodies with any standard library.
#pragma once

#include "world/model.hpp"

namespace tem {

// Appends fill.count copies of `copy` (already built, its blocks in model.blocks) to
// model.bodies, named fill.name + "_" + index, avoiding every body already in the model. Throws
// SceneError at the fill's path when a name is taken or the copies do not fit.
void place_fill(const FillDef& fill, const Body& copy, Model& model);

// A rotation drawn uniformly from all rotations, from three numbers uniform in [0, 1)
// (Shoemake's method).
Mat3 uniform_rotation(Real u1, Real u2, Real u3);

}  // namespace tem
