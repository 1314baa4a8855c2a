// Default SEMM by patch blocks (solve_semm, semm.hpp) as a force model (force_model.hpp):
// contact.model "semm" with contact.solver "blocks". The blocks solver is the SEMM core's own
// (the overlap correction solves its separation with it too), so this folder holds only the
// model around it.
#pragma once

#include "forces/force_model.hpp"

namespace tem {

const ForceModel& semm_blocks_model();

}  // namespace tem
