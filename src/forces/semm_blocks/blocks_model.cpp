#include "forces/semm_blocks/blocks_model.hpp"

#include "forces/semm_step.hpp"

namespace tem {
namespace {

class BlocksModel final : public DefaultSemmModel {
 public:
  void compute(const ForceStep& step, ContactForces& f) const override {
    if (!begin_semm_step(step, f)) return;
    const SolverSettings settings = begin_default_semm(step, f);
    f.solver = solve_semm(f.points, f.approach, f.responses, f.centres, settings, f.friction,
                          f.impulses);
    semm_impulses_to_forces(step.dt, true, f);
  }
  // By patch blocks, as the step.
  void separate(const std::vector<Real>& targets, const SolverSettings& stopping,
                ContactForces& f) const override {
    solve_separation(f.points, targets, f.correction.still, f.centres, f.correction.patches,
                     f.correction.impulses, f.correction.moved, stopping);
  }
  std::string not_distributed_because() const override {
    return "over MPI ranks SEMM runs with contact.solver 'rows'; 'blocks' is not "
           "distributed: run this scene without mpirun, or with the rows solver";
  }
};

}  // namespace

const ForceModel& semm_blocks_model() {
  static const BlocksModel model;
  return model;
}

}  // namespace tem
