// Convex hulls of mesh parts (Qhull): their volume, for scoring cuts, and a polyhedron that
// Block accepts, for the blocks themselves.
#pragma once

#include <optional>
#include <vector>

#include "geometry/block.hpp"

namespace tem {

// Volume of the convex hull of the points; 0 when they span no volume.
Real hull_volume(const std::vector<Vec3>& points);

// Largest distance of the points from their mean: the size Block measures its tolerance by, and
// so the scale of a weld distance.
Real radius_about_mean(const std::vector<Vec3>& points);

// The convex hull of any points as Qhull gives it (its vertices in the points' order, coplanar
// facets merged into polygons counter-clockwise about their outward normals), not checked as a
// block: for sampling a hull's surface, where hull_block's welding and checks
// would cost more than the samples. Nothing when the points span no 3-d hull.
std::optional<PolyhedronDef> hull_polyhedron(const std::vector<Vec3>& points);

// The convex hull of any points (repeats and interior points allowed) as a PolyhedronDef that
// Block accepts, or nothing when they span no usable volume. Hull vertices closer than `weld`
// are welded first (one of them kept), and any vertex that would break one of Block's checks
// with its tolerance divided by `margin` (a corner too flat, a facet not flat enough, a sliver
// facet) is dropped and the hull taken again. The result is the hull of a subset of the points,
// so it lies inside their hull (and a part's block inside its cell); the points dropped are
// near-repeats and corners within a hair of their neighbours' hull, so it is hardly smaller.
std::optional<PolyhedronDef> hull_block(const std::vector<Vec3>& points, Real weld,
                                        Real margin = 10);

}  // namespace tem
