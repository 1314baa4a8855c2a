// The one place that knows every force model (force_model.hpp).
#include "forces/force_model.hpp"

#include <stdexcept>

#include "forces/penalty/penalty_model.hpp"
#include "forces/semm_blocks/blocks_model.hpp"
#include "forces/semm_newton/newton_model.hpp"
#include "forces/semm_paper/paper_model.hpp"
#include "forces/semm_rows/rows_model.hpp"

namespace tem {

void ForceModel::separate(const std::vector<Real>& /*targets*/,
                          const SolverSettings& /*stopping*/, ContactForces& /*f*/) const {
  throw std::logic_error("the overlap correction asked its move of a force model that does not "
                         "correct overlap");
}

const ForceModel& force_model(const ContactDef& contact) {
  switch (contact.model) {
    case ContactModel::penalty:
      return penalty_model();
    case ContactModel::semm_paper:
      return semm_paper_model();
    case ContactModel::semm:
      break;
  }
  switch (contact.solver) {
    case ContactSolver::blocks:
      return semm_blocks_model();
    case ContactSolver::newton:
      return semm_newton_model();
    case ContactSolver::rows:
      break;
  }
  return semm_rows_model();
}

}  // namespace tem
