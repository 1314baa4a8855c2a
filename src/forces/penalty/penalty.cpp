#include "forces/penalty/penalty.hpp"

#include "forces/body_response.hpp"
#include "forces/materials.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace tem {
namespace {

// The spring of the last step for this patch: same pair, nearest within 1% of A's size. The
// last step's springs are in patch order, so the pair's are found by bisection, not by a scan
// of all of them (which made a pile's force stage quadratic in its contacts).
Vec3 remembered_stretch(const Model& model, const std::vector<PenaltySpring>& old,
                        const ContactPatch& p) {
  const Real reach = 0.01 * body_size(model, p.body_a);
  const PenaltySpring* best = nullptr;
  Real best_distance = reach;
  const auto key = pair_key(p);
  const auto first = std::lower_bound(
      old.begin(), old.end(), key,
      [](const PenaltySpring& s, const decltype(key)& k) { return pair_key(s) < k; });
  for (auto it = first; it != old.end() && pair_key(*it) == key; ++it) {
    const PenaltySpring& s = *it;
    const Real d = (s.point - p.point).norm();
    if (d < best_distance) {
      best_distance = d;
      best = &s;
    }
  }
  if (!best) return Vec3::Zero();
  // Turned into the current tangent plane, keeping its length.
  const Vec3 flat = best->stretch - best->stretch.dot(p.normal) * p.normal;
  const Real n = flat.norm();
  return n > 0 ? Vec3(flat * (best->stretch.norm() / n)) : Vec3::Zero();
}

// World inverse inertia of a body that the contact turns (none for walls and driven bodies).
Mat3 inverse_inertia_world(const Model& model, const State& state, int body) {
  if (body < 0 || model.bodies[body].driven()) return Mat3::Zero();
  const Mat3& g = state.bodies[body].g;
  return g * model.bodies[body].inertia.inertia_inv * g.transpose();
}

Vec3 spin(const Model& model, const State& state, int body) {
  if (body < 0 || model.bodies[body].fixed) return Vec3::Zero();
  return state.bodies[body].angular_velocity_world();
}

// Rolling resistance (materials.hpp): the torque on B, -mu_r R F_n along the relative rolling
// velocity w (omega_B - omega_A off the normal n), but no more than stops that rolling within
// the step, w / (dt w^.(Q_A + Q_B) w^) with Q the world inverse inertias: it never reverses the
// rolling, so it only takes energy out.
Vec3 rolling_torque(const Model& model, const State& state, const ContactPatch& p, Real limit,
                    Real dt) {
  const Vec3 w = spin(model, state, p.body_b) - spin(model, state, p.body_a);
  const Vec3 rolling = w - w.dot(p.normal) * p.normal;
  const Real speed = rolling.norm();
  if (!(speed > 0)) return Vec3::Zero();
  const Vec3 along = rolling / speed;
  const Real k = along.dot((inverse_inertia_world(model, state, p.body_a) +
                            inverse_inertia_world(model, state, p.body_b)) *
                           along);
  if (!(k > 0)) return Vec3::Zero();
  return -std::min(limit, speed / (dt * k)) * along;
}

}  // namespace

void penalty_forces(const Model& model, const State& state,
                    const std::vector<ContactPatch>& patches,
                    const std::vector<ContactPoint>& points, const std::vector<Vec3>& centres,
                    std::vector<PenaltySpring>& springs,
                    std::vector<Vec3>& force, std::vector<Vec3>& torque,
                    std::vector<Real>& normal_magnitude, std::vector<Real>& tangential_magnitude) {
  const ContactDef& c = model.scene.contact;
  const Real dt = model.scene.time_step;
  assert(std::is_sorted(springs.begin(), springs.end(),
                        [](const PenaltySpring& x, const PenaltySpring& y) {
                          return pair_key(x) < pair_key(y);
                        }));
  const bool hertz = c.law == PenaltyLaw::hertz;
  std::vector<PenaltySpring> next;
  next.reserve(patches.size());
  normal_magnitude.assign(patches.size(), 0);
  tangential_magnitude.assign(patches.size(), 0);
  auto push = [&](const ContactPatch& p, const Vec3& at, const Vec3& on_b) {
    add_contact_force(centres, p.body_a, p.body_b, at, on_b, Vec3::Zero(), force, torque);
  };
  for (size_t i = 0; i < points.size();) {
    const int k = points[i].patch;
    const ContactPatch& p = patches[k];
    const Vec3& n = p.normal;
    size_t last = i;
    while (last < points.size() && points[last].patch == k) ++last;
    // Normal: the patch's spring and dashpot, never pulling, shared among its points in
    // proportion to their depths (a tilted face pushes back hardest where it is deepest); with
    // no depth at any point (all are edge crossings), at the patch's point.
    const Real depth = std::max<Real>(p.depth, 0);
    const Real approach = -n.dot(material_point_velocity(model, state, p.body_b, p.point) -
                                 material_point_velocity(model, state, p.body_a, p.point));
    const Real spring = hertz ? c.stiffness * depth * std::sqrt(depth) : c.stiffness * depth;
    const Real dashpot =
        hertz ? c.damping * std::pow(depth, 0.25) * approach : c.damping * approach;
    const Real fn = std::max<Real>(0, spring + dashpot);
    Real total_depth = 0;
    for (size_t q = i; q < last; ++q) total_depth += std::max<Real>(points[q].depth, 0);
    if (total_depth > 0) {
      for (size_t q = i; q < last; ++q)
        push(p, points[q].point, fn * std::max<Real>(points[q].depth, 0) / total_depth * n);
    } else {
      push(p, p.point, fn * n);
    }
    i = last;
    // Tangential: the patch's spring stretches with the slip at its centre; at the Coulomb
    // limit it slides.
    // A belt's sliding surface (motion.surface_velocity) adds its tangential part.
    const Vec3 u = material_point_velocity(model, state, p.body_b, p.point) -
                   material_point_velocity(model, state, p.body_a, p.point) +
                   surface_velocity(model, p.body_b, state.time) -
                   surface_velocity(model, p.body_a, state.time);
    const Vec3 slip = u - u.dot(n) * n;
    const Real kt = hertz ? c.tangential_stiffness * std::sqrt(depth) : c.tangential_stiffness;
    const Real ct = c.stiffness > 0 ? c.damping * c.tangential_stiffness / c.stiffness : 0;
    Vec3 stretch = remembered_stretch(model, springs, p) + slip * dt;
    const PairCoefficients& coefficients = contact_coefficients(model, p.body_a, p.body_b, p.wall);
    const Real limit = coefficients.friction * fn;
    if (kt * stretch.norm() > limit) stretch *= limit / (kt * stretch.norm());
    Vec3 ft = -kt * stretch - ct * slip;  // on B
    if (ft.norm() > limit) ft *= limit / ft.norm();
    push(p, p.point, ft);
    if (coefficients.rolling_resistance > 0 && fn > 0) {
      const Real radius = rolling_radius(model, state, p.body_a, p.body_b, p.point);
      const Vec3 moment =
          rolling_torque(model, state, p, coefficients.rolling_resistance * radius * fn, dt);
      add_contact_force(centres, p.body_a, p.body_b, p.point, Vec3::Zero(), moment, force,
                        torque);
    }
    normal_magnitude[k] = fn;
    tangential_magnitude[k] = ft.norm();
    next.push_back({p.body_a, p.body_b, p.wall, p.point, stretch});
  }
  springs = std::move(next);
}

Real penalty_time_step_limit(const Model& model) {
  const ContactDef& c = model.scene.contact;
  Real limit = std::numeric_limits<Real>::infinity();
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].driven() || !(c.stiffness > 0)) continue;
    Real k = c.stiffness;
    if (c.law == PenaltyLaw::hertz)
      k = 1.5 * c.stiffness * std::sqrt(0.01 * body_size(model, static_cast<int>(b)));
    const Real period = 2 * std::numbers::pi * std::sqrt(model.bodies[b].inertia.mass / k);
    limit = std::min(limit, period / 10);
  }
  return limit;
}

}  // namespace tem
