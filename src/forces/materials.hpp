// Per-contact coefficients from materials (docs/method.md "Materials"): each patch takes the
// friction, restitution and rolling resistance of the pair of materials of its two sides
// (Model::coefficients: contact.pairs where they name the pair, else the smaller friction, the
// smaller restitution and the larger rolling resistance; material 0, none, is contact.friction,
// contact.restitution and no rolling resistance). Shared by the SEMM solvers and the penalty
// model; a table lookup per patch, once per step.
//
// Rolling resistance is the constant directional torque model (LIGGGHTS' epsd2, Chrono, Lethe):
// a torque on B, its opposite on A, against the relative rolling angular velocity (the part of
// omega_B - omega_A perpendicular to the patch normal), of size at most mu_r R F_n, with F_n
// the patch's normal force and R a rolling radius.
//
// The rolling radius of a polyhedron. For spheres R is the effective radius r_a r_b / (r_a + r_b)
// of the two radii; a polyhedron has no radius, and where it rolls it rolls about the point of
// contact at the distance from its centre of mass to that point (a ball-like hull or a prism on
// its side: its circumradius, the same r as the sphere's). So each side contributes r = |patch
// point - its centre of mass|, combined as for spheres. A wall contributes none (R = r_a, a
// sphere on a plane), and so does a driven body (fixed, or with a prescribed motion): such
// bodies are the scenery (plates, floors, drums) whose centre of mass can lie anywhere, e.g. a
// thin plate's centre half its thickness below a ball on it, which would make R tiny; like a
// wall, their surface is taken as flat.
#pragma once

#include "dynamics/body_state.hpp"
#include "world/model.hpp"

namespace tem {

// The coefficients of the pair body A (always a body) and body B, or the wall when body_b < 0.
inline const PairCoefficients& contact_coefficients(const Model& model, int body_a, int body_b,
                                                    int wall) {
  const int a = model.bodies[body_a].material;
  const int b = body_b >= 0 ? model.bodies[body_b].material
                : wall >= 0  ? model.walls[wall].material
                             : 0;
  return model.coefficients(a, b);
}

// The rolling radius R at `point` (above); 0 when neither side counts (both driven).
inline Real rolling_radius(const Model& model, const State& state, int body_a, int body_b,
                           const Vec3& point) {
  auto radius = [&](int body) -> Real {
    if (body < 0 || model.bodies[body].driven()) return 0;
    return (point - state.bodies[body].x).norm();
  };
  const Real ra = radius(body_a), rb = radius(body_b);
  if (ra > 0 && rb > 0) return ra * rb / (ra + rb);
  return ra > 0 ? ra : rb;
}

}  // namespace tem
