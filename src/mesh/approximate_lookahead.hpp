// A look one cut ahead for the approximate cutter. The sum of the two sides' hull volumes alone
// is short-sighted: halving a ring leaves two C shapes whose hulls still fill the hole, so it
// gains nothing, while shaving its top and bottom gains a little; only the next cuts show which
// was right. Here a side's next cut is tried cheaply, on a thinned cloud of its corners.
#pragma once

#include <vector>

#include "tem/types.hpp"

namespace tem {

// How much the hull volume of a part with these corners drops at best when it is cut once more
// by a plane through its centre normal to one of its principal axes: estimated on
// at most about kCloudCells^2 of the points (one per cell of a grid), each side's hull taking in
// the points just across the plane moved onto it (they stand for the cap).
Real lookahead_gain(const std::vector<Vec3>& corners);

// The first of the points in each cell of a grid of `cells` cells along their longest extent
// (in the points' order, so the same every run): a hull of these is the points' hull to within
// about a cell, at a fraction of the cost.
std::vector<Vec3> thinned_cloud(const std::vector<Vec3>& points, int cells);

}  // namespace tem
