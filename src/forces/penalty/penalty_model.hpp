// The penalty model as a force model (force_model.hpp): contact.model "penalty" (penalty.hpp).
#pragma once

#include "forces/force_model.hpp"

namespace tem {

const ForceModel& penalty_model();

}  // namespace tem
