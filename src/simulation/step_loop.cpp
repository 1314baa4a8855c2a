#include "simulation/step_loop.hpp"

#include "simulation/sleep.hpp"

namespace tem {

void find_forces(const Model& model, State& state, Workspace& w, StepHooks& hooks) {
  w.loads.update_active();
  hooks.before_forces(model, state, w);
  find_contact_forces(model, state, w);
  hooks.after_forces(w);
}

void take_step(Model& model, State& state, Workspace& w, std::vector<RemovedBody>& removed,
               StepHooks& hooks) {
  hooks.step_begins(model, state, w);
  find_forces(model, state, w, hooks);
  hooks.forces_found(model, state, w);
  advance(model, state, w);
  if (model.bodies_come_and_go) {
    const size_t removed_before = removed.size();
    update_population(model, state,
                      {&w.forces, &w.patches, &w.loads, &w.contact.features}, removed);
    // Sleeping bodies near those taken away wake (sleep.hpp); the copies just placed are awake.
    if (model.scene.sleep && removed.size() > removed_before)
      wake_near_removed(model, removed, removed_before, state);
    hooks.bodies_left(removed);
    removed.clear();
  }
}

}  // namespace tem
