#include "forces/contact_forces.hpp"

#include "forces/solver_sync.hpp"

namespace tem {

void compute_contact_forces(const Model& model, const State& state,
                            const std::vector<ContactPatch>& patches, Real dt, ContactForces& f,
                            const ExternalLoads* loads, SolverSync* sync) {
  const size_t n_bodies = model.bodies.size();
  f.force.assign(n_bodies, Vec3::Zero());
  f.torque.assign(n_bodies, Vec3::Zero());
  f.patch_forces.assign(patches.size(), PatchForce{});
  f.patch_depth.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k) f.patch_depth[k] = patches[k].depth;
  f.solver = SolverReport{};
  f.centres.resize(n_bodies);
  for (size_t b = 0; b < n_bodies; ++b) f.centres[b] = state.bodies[b].x;
  force_model(model.scene.contact).compute(ForceStep{model, state, patches, dt, loads, sync}, f);
}

}  // namespace tem
