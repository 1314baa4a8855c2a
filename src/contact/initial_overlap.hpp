// Overlap at the start of a run. Bodies placed into each other (a typing mistake in a position,
// a fill too dense) are pushed apart by the first steps with whatever energy that takes, which
// is rarely what the user meant; so a run or a check names them before it starts.
#pragma once

#include <string>
#include <vector>

#include "world/model.hpp"

namespace tem {

struct InitialOverlap {
  int body_a = -1, body_b = -1, wall = -1;  // body_b -1 for a wall
  Real depth = 0;                           // the deepest patch between them
  Real relative = 0;                        // depth / size of the smaller body (its own for a wall)
};

// Every pair of bodies (or body and wall) whose deepest contact patch at the initial state is
// deeper than `fraction` of the smaller body's size (body_size), deepest first.
std::vector<InitialOverlap> deep_initial_overlaps(const Model& model, Real fraction = 0.01);

// "bodies 'a' and 'b' overlap by 0.02 (13% of the smaller one's size) at the start".
std::string describe(const Model& model, const InitialOverlap& overlap);

}  // namespace tem
