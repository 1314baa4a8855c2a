// A TEM Model rebuilt as a Bullet world (btDiscreteDynamicsWorld), and Bullet's state read back
// as a TEM State, so that TEM's own measures (bench/peers/tem_measures.hpp) judge every engine
// alike.
#pragma once

#include <memory>
#include <vector>

#include "dynamics/body_state.hpp"
#include "peer_world.hpp"
#include "world/model.hpp"

class btDefaultCollisionConfiguration;
class btCollisionDispatcher;
class btBroadphaseInterface;
class btSequentialImpulseConstraintSolver;
class btDiscreteDynamicsWorld;
class btCollisionShape;
class btRigidBody;

namespace tem::bullet {

struct BulletSettings {
  // Collision margin in scene units (cm): Bullet inflates every hull by it.
  Real margin = 0;
  // Coulomb friction and restitution wanted for every contact (body-body and body-wall).
  Real friction = 0.3;
  Real restitution = 0;
  // Let bodies at rest fall asleep (Bullet's default); off keeps every body simulated.
  bool sleeping = true;
};

class BulletWorld : public peers::PeerWorld {
 public:
  // Every Model body becomes a btRigidBody (static when fixed), every Model wall a static plane;
  // poses and velocities come from `initial`.
  BulletWorld(const Model& model, const State& initial, const BulletSettings& settings);
  ~BulletWorld() override;
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  // One step of exactly dt: no substeps, no interpolation.
  void step(Real dt) override;

  // Centres of mass, attitudes (body frame of the Model to world) and velocities.
  State state() const override;

  int sleeping_bodies() const override;

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;  // hulls, compounds, planes
  std::vector<std::unique_ptr<btRigidBody>> bodies_;       // Model bodies first, then walls
  // Per Model body: the principal axes in the Model's body frame (columns), see the .cpp.
  std::vector<Mat3> principal_;
  int body_count_ = 0;
};

}  // namespace tem::bullet
