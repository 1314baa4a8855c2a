// SEMM by Newton's method (semm_newton.hpp) as a force model (force_model.hpp):
// contact.model "semm" with contact.solver "newton".
#pragma once

#include "forces/force_model.hpp"

namespace tem {

const ForceModel& semm_newton_model();

}  // namespace tem
