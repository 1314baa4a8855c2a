// What the side-by-side programs (tem_bullet, tem_ode) need of another engine's world built from
// a TEM scene: a step of exactly dt, and its state read back as a TEM State, so that TEM's own
// measures (tem_measures.hpp, system_energies) judge every engine alike.
#pragma once

#include "dynamics/body_state.hpp"
#include "tem/types.hpp"

namespace tem::peers {

class PeerWorld {
 public:
  virtual ~PeerWorld() = default;

  // One step of exactly dt: no substeps, no interpolation.
  virtual void step(Real dt) = 0;

  // Per Model body: centre of mass, attitude (body frame of the Model to world), velocity of the
  // centre of mass (world) and angular velocity in the Model's body axes (BodyState::omega).
  virtual State state() const = 0;

  // Bodies the engine has put to sleep (deactivated); 0 where it has no such thing.
  virtual int sleeping_bodies() const = 0;
};

}  // namespace tem::peers
