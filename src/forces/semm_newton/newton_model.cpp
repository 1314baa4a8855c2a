#include "forces/semm_newton/newton_model.hpp"

#include "forces/semm_step.hpp"

namespace tem {
namespace {

class NewtonModel final : public DefaultSemmModel {
 public:
  void compute(const ForceStep& step, ContactForces& f) const override {
    if (!begin_semm_step(step, f)) return;
    const SolverSettings settings = begin_default_semm(step, f);
    normal_targets(f.points, f.approach, f.approach_linear, settings, f.targets, &f.friction);
    f.solver = solve_semm_newton(f.points, f.approach, f.targets, f.responses, f.centres, settings,
                                 f.friction, f.impulses, f.newton);
    semm_impulses_to_forces(step.dt, true, f);
  }
  std::string not_distributed_because() const override {
    return "over MPI ranks SEMM runs with contact.solver \"rows\"; \"newton\" (the default) is "
           "not distributed: add \"solver\": \"rows\" to the scene's contact, or run it "
           "without mpirun (threads: --threads N)";
  }
};

}  // namespace

const ForceModel& semm_newton_model() {
  static const NewtonModel model;
  return model;
}

}  // namespace tem
