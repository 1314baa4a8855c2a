// What an inlet owes and what it can deliver (docs/processes.md, "Inlets"): the copies due by a
// time, and the warnings of a scene whose inlets would deliver less than they say without a
// word otherwise: a start at or after the run's end, a count the rate cannot reach in the run,
// a region with no room among the fixed bodies and walls, a region that feeds an outlet.
#pragma once

#include <string>
#include <vector>

#include "world/model.hpp"

namespace tem {

// Copies an inlet owes by time t: the first at `start`, then one every 1/rate, at most `count`.
long long copies_due(const InletDef& inlet, Real t);

// The warnings, each starting with the JSON path it is about, for `model` as built (bodies at
// their start poses).
std::vector<std::string> inlet_warnings(const Model& model);

}  // namespace tem
