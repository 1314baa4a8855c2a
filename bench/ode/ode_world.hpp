// A TEM Model rebuilt as an ODE world (Open Dynamics Engine 0.16, Debian's libode-dev), and
// ODE's state read back as a TEM State, so that TEM's own measures (bench/peers/) judge it as
// they judge TEM and Bullet.
//
// How the world is built (docs/benchmarks.md "Pour side by side"):
//  - every TEM body is one dBody whose frame is TEM's body frame (origin at the centre of mass,
//    the scene's axes), with TEM's mass and full inertia tensor (dMassSetParameters: ODE takes
//    the off-diagonal terms, so nothing is diagonalised);
//  - every block of a body is one dConvex geom on that dBody, its nodes and face planes already
//    placed in the body frame (no geom offset to update per step);
//  - every wall (the container's faces among them) is a static dPlane;
//  - contacts: dCollide with at most `max_contacts` points per pair of geoms, each a contact
//    joint with Coulomb friction by ODE's pyramid approximation (dContactApprox1: the friction
//    bound follows the normal force) and the pair's restitution;
//  - the step is dWorldQuickStep (iterative, `iterations` sweeps) or dWorldStep (ODE's direct
//    LCP solver, dense per island: usable only for small scenes), with the world's ERP and CFM.
#pragma once

#include <memory>
#include <vector>

#include "peer_world.hpp"
#include "world/model.hpp"

namespace tem::ode {

struct OdeSettings {
  bool quick_step = true;  // dWorldQuickStep; false: dWorldStep
  int iterations = 20;     // dWorldQuickStep's sweeps (ODE's default)
  // Error reduction (the fraction of the overlap removed per step) and constraint force mixing
  // (softness), for every contact; ODE's defaults are 0.2 and 1e-5.
  Real erp = 0.2;
  Real cfm = 1e-5;
  // ODE lets contacts sink this deep before pushing them apart (dWorldSetContactSurfaceLayer).
  Real surface_layer = 0;
  int max_contacts = 8;  // contact points per pair of geoms
  // Blocks as dTriMesh geoms (their surface triangles) instead of dConvex: ODE's convex-convex
  // test gives one contact point per pair, its trimesh-trimesh test several.
  bool trimesh = false;
  // Negative: each pair's coefficients from the Model (contact.friction, materials).
  Real friction = -1;
  Real restitution = -1;
  // ODE's auto-disable with its default thresholds; off: every body simulated to the end.
  bool sleeping = true;
};

class OdeWorld : public peers::PeerWorld {
 public:
  OdeWorld(const Model& model, const State& initial, const OdeSettings& settings);
  ~OdeWorld() override;
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  void step(Real dt) override;
  State state() const override;
  int sleeping_bodies() const override;

  struct Impl;  // ODE's handles and the convex data they point to

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tem::ode
