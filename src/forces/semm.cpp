#include "forces/semm.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>

#include "forces/patch_colouring.hpp"
#include "forces/semm_rows/semm_rows.hpp"
#include "support/parallel.hpp"

namespace tem {
namespace {

using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Mat2 = Eigen::Matrix<Real, 2, 2>;

// One side of a contact: the body's pseudo velocities (updated as impulses are applied), its
// response and the lever arm from its centre of mass. A wall or a fixed body has no response
// and stays still.
struct Side {
  BodyResponse* body = nullptr;
  Vec3 arm = Vec3::Zero();

  Vec3 point_velocity() const {
    return body ? Vec3(body->velocity + body->angular_velocity.cross(arm)) : Vec3::Zero();
  }
  Vec3 spin() const { return body ? body->angular_velocity : Vec3::Zero(); }
  // A linear impulse j at the arm's end and an angular impulse h.
  void apply(const Vec3& j, const Vec3& h) {
    if (!body) return;
    body->velocity += body->inverse_mass * j;
    body->angular_velocity += body->angular * (arm.cross(j) + h);
  }
  // Change of the point velocity and the spin for (j, h), without applying it.
  std::pair<Vec3, Vec3> response(const Vec3& j, const Vec3& h) const {
    if (!body) return {Vec3::Zero(), Vec3::Zero()};
    const Vec3 dw = body->angular * (arm.cross(j) + h);
    return {body->inverse_mass * j + dw.cross(arm), dw};
  }
};

Side side_of(std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres, int body,
             const Vec3& point) {
  Side s;
  if (body >= 0 && (bodies[body].inverse_mass > 0 || bodies[body].driven)) {
    s.body = &bodies[body];
    s.arm = point - centres[body];
  }
  return s;
}

// The normal impulses of one patch are solved together: the points of one patch push on the
// same two bodies and are strongly coupled (a tall column on its end rocks on them), which
// point-by-point Gauss-Seidel resolves only after thousands of sweeps. A patch has at most
// eight points (contact_points.hpp).
constexpr int kMaxBlock = 8;
using BlockMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlock, kMaxBlock>;
using BlockVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxBlock, 1>;

using BlockFactor = Eigen::LDLT<BlockMatrix>;

// The regularisation of a patch's block: redundant points make K singular; 1e-13 of its
// largest diagonal entry picks one of the equivalent answers.
Real block_regularisation(const BlockMatrix& k) {
  return 1e-13 * std::max<Real>(k.diagonal().maxCoeff(), 1e-300);
}

// min 1/2 x.K x + q.x over x >= 0 (K symmetric positive semi-definite), by the active-set
// method of Lawson and Hanson, from the feasible start x. `all_free` is the factorisation of
// the regularised K, made once per step: in resting contact every point pushes, and then the
// answer is that of the whole block, the same numbers the active-set iterations would end with,
// found without factorising at every sweep.
void solve_block(const BlockMatrix& k, const BlockFactor& all_free, bool well_conditioned,
                 const BlockVector& q, BlockVector& x) {
  const int m = static_cast<int>(q.size());
  // Only where K is far from singular: with redundant points (four corners of a face pushing
  // on one plane) the regularised whole block amplifies rounding into large, opposed impulses;
  // the active set keeps the ones it has.
  if (well_conditioned) {
    const BlockVector z = all_free.solve(-q);
    if ((z.array() > 0).all()) {
      x = z;
      return;
    }
  }
  const Real eps = block_regularisation(k);
  const Real tolerance = 1e-12 * std::max<Real>(q.cwiseAbs().maxCoeff(), 1e-300);
  std::array<bool, kMaxBlock> free{};
  for (int i = 0; i < m; ++i) free[i] = x(i) > 0;
  for (int outer = 0; outer < 3 * m + 3; ++outer) {
    // Optimal on the free set, staying feasible.
    for (int inner = 0; inner <= m; ++inner) {
      std::array<int, kMaxBlock> index{};
      int f = 0;
      for (int i = 0; i < m; ++i)
        if (free[i]) index[f++] = i;
      BlockVector z = BlockVector::Zero(m);
      if (f > 0) {
        BlockMatrix kf(f, f);
        BlockVector qf(f);
        for (int r = 0; r < f; ++r) {
          qf(r) = q(index[r]);
          for (int c = 0; c < f; ++c) kf(r, c) = k(index[r], index[c]);
          kf(r, r) += eps;
        }
        const BlockVector zf = kf.ldlt().solve(-qf);
        for (int r = 0; r < f; ++r) z(index[r]) = zf(r);
      }
      // Step towards z until a free impulse reaches zero; that one (exactly zero, not a
      // rounding residue that would stall the next steps) leaves the free set.
      Real alpha = 1;
      int blocking = -1;
      for (int i = 0; i < m; ++i)
        if (free[i] && z(i) <= 0) {
          const Real a = x(i) / (x(i) - z(i));
          if (a < alpha) {
            alpha = a;
            blocking = i;
          }
        }
      if (blocking < 0) {
        x = z;
        break;
      }
      x += alpha * (z - x);
      x(blocking) = 0;
      free[blocking] = false;
      for (int i = 0; i < m; ++i)
        if (free[i] && x(i) <= 0) {
          x(i) = 0;
          free[i] = false;
        }
    }
    // The most negative gradient among the bound points joins the free set.
    const BlockVector w = k * x + q;
    int join = -1;
    Real most = -tolerance;
    for (int i = 0; i < m; ++i)
      if (!free[i] && w(i) < most) {
        most = w(i);
        join = i;
      }
    if (join < 0) return;
    free[join] = true;
  }
}

struct NormalRow {
  Side a, b;
  Vec3 normal;
  Real k = 0;       // n.K n: change of the normal relative velocity per unit impulse
  Real target = 0;  // required normal relative velocity after the step
  int patch = 0;    // index into the friction rows
};

struct FrictionRow {
  Side a, b;
  BlockMatrix k_normal;  // n_i.K n_j of the patch's points
  BlockFactor k_normal_factor;  // of k_normal + its regularisation (solve_block)
  bool k_normal_well_conditioned = false;
  Mat2 k_slip;       // tangential block of K at the centre
  Real k_twist = 0;  // twist block
  Vec3 start_slip;   // (t1, t2, spin) at the start of the step
  Real reach = 0;    // sum over points of normal impulse x distance, updated each sweep
  Real mu = 0;       // the patch's friction coefficient
  // Rolling resistance: the limit per unit normal impulse (mu_r R; 0: no rolling block), the
  // angular block of K about the tangents, the rolling velocity at the start of the step.
  Real rolling_limit = 0;
  Mat2 k_roll = Mat2::Zero();
  Vec2 start_roll = Vec2::Zero();
};

// Relative (t1, t2, spin) of B over A at a friction row's centre.
Vec3 slip(const FrictionRow& f, const PatchFriction& p) {
  const Vec3 dv = f.b.point_velocity() - f.a.point_velocity();
  return Vec3(p.tangent1.dot(dv), p.tangent2.dot(dv), p.normal.dot(f.b.spin() - f.a.spin()));
}

// Applies a friction impulse (t1, t2, twist) on B, its opposite on A.
void apply_friction(FrictionRow& f, const PatchFriction& p, const Vec3& d) {
  const Vec3 j = d.x() * p.tangent1 + d.y() * p.tangent2, h = d.z() * p.normal;
  f.b.apply(j, h);
  f.a.apply(-j, -h);
}

// The unconstrained minimiser of one block of friction, then scaled into its limit. If sticking
// would push along the slip the contact started the step with (the load turns it round within
// the step), that impulse would add the energy dt/2 f.(u_start + u_after); the block then asks
// for the slip to end as it started, mirrored, which adds none.
template <class Vec, class Mat>
Vec friction_block(const Vec& now, const Vec& velocity, const Vec& start, const Mat& k,
                   Real limit) {
  Vec f = now - k.ldlt().solve(velocity);
  if (f.dot(start) > 0) f = now - k.ldlt().solve(velocity + start);
  const Real size = f.norm();
  if (size > limit) f *= limit / size;
  return f;
}

// One patch's normal impulses, solved together (non-negative, exact for the block).
void normal_update(int k, std::vector<NormalRow>& rows, std::vector<FrictionRow>& friction,
                   const std::vector<PatchFriction>& patches,
                   std::vector<PointImpulse>& impulses, SweepSize& size) {
  const PatchFriction& p = patches[k];
  const int m = p.last - p.first;
  BlockVector now(m), q(m);
  for (int r = 0; r < m; ++r) {
    const NormalRow& row = rows[p.first + r];
    now(r) = impulses[p.first + r].normal;
    q(r) = row.normal.dot(row.b.point_velocity() - row.a.point_velocity()) - row.target;
  }
  q -= friction[k].k_normal * now;  // the velocities without this block's impulses
  BlockVector after = now;
  solve_block(friction[k].k_normal, friction[k].k_normal_factor,
              friction[k].k_normal_well_conditioned, q, after);
  for (int r = 0; r < m; ++r) {
    NormalRow& row = rows[p.first + r];
    const Real d = after(r) - now(r);
    impulses[p.first + r].normal = after(r);
    row.b.apply(d * row.normal, Vec3::Zero());
    row.a.apply(-d * row.normal, Vec3::Zero());
    size.add(std::abs(d), after(r));
  }
}

// Applies a rolling angular impulse (about tangent1, tangent2) on B, its opposite on A.
void apply_rolling(FrictionRow& f, const PatchFriction& p, const Vec2& d) {
  const Vec3 h = d.x() * p.tangent1 + d.y() * p.tangent2;
  f.b.apply(Vec3::Zero(), h);
  f.a.apply(Vec3::Zero(), -h);
}

// One patch's rolling resistance: the 2x2 minimiser of its rolling impulse, with the energy rule
// of friction_block, scaled into the disc mu_r R (patch normal impulse).
void rolling_update(FrictionRow& f, PatchFriction& p, Real total, SweepSize& size) {
  const Vec3 dw = f.b.spin() - f.a.spin();
  const Vec2 u(p.tangent1.dot(dw), p.tangent2.dot(dw)), now(p.roll1, p.roll2);
  const Vec2 h = friction_block<Vec2, Mat2>(now, u, f.start_roll, f.k_roll,
                                            f.rolling_limit * total);
  apply_rolling(f, p, h - now);
  p.roll1 = h.x();
  p.roll2 = h.y();
  // An angular impulse: compared on the patch's scale, divided by the rolling radius.
  size.add((h - now).norm() / p.rolling_radius, h.norm() / p.rolling_radius);
}

// One patch's friction: tangential, then twist, each within its Coulomb limit; then its
// rolling resistance, if any.
void friction_update(int k, std::vector<FrictionRow>& friction,
                     std::vector<PatchFriction>& patches, const std::vector<ContactPoint>& points,
                     const std::vector<PointImpulse>& impulses, SweepSize& size) {
  PatchFriction& p = patches[k];
  FrictionRow& f = friction[k];
  const Real mu = f.mu;
  if (!(mu > 0) && !(f.rolling_limit > 0)) return;
  Real total = 0, reach = 0;
  for (int i = p.first; i < p.last; ++i) {
    total += impulses[i].normal;
    reach += impulses[i].normal * (points[i].point - p.centre).norm();
  }
  if (f.rolling_limit > 0) rolling_update(f, p, total, size);
  if (!(mu > 0)) return;
  const Vec3 before(p.t1, p.t2, p.twist);
  Vec3 u = slip(f, p);
  const Vec2 t = friction_block<Vec2, Mat2>(Vec2(p.t1, p.t2), u.head<2>(),
                                            f.start_slip.head<2>(), f.k_slip, mu * total);
  apply_friction(f, p, Vec3(t.x() - p.t1, t.y() - p.t2, 0));
  p.t1 = t.x();
  p.t2 = t.y();
  if (f.k_twist > 0) {
    using One = Eigen::Matrix<Real, 1, 1>;
    u = slip(f, p);
    const One twist = friction_block<One, One>(One(p.twist), One(u.z()), One(f.start_slip.z()),
                                               One(f.k_twist), mu * reach);
    apply_friction(f, p, Vec3(0, 0, twist(0) - p.twist));
    p.twist = twist(0);
  }
  const Vec3 after(p.t1, p.t2, p.twist);
  // Twist is an impulse times a length: compare it on the patch's own scale.
  const Real scale = reach > 0 && total > 0 ? total / reach : 0;
  size.add((after - before).head<2>().norm() + scale * std::abs(after.z() - before.z()),
           after.head<2>().norm());
}

SolverReport sweep(std::vector<NormalRow>& rows, std::vector<FrictionRow>& friction,
                   std::vector<PatchFriction>& patches, const std::vector<ContactPoint>& points,
                   const std::vector<int>& colours, const SolverSettings& settings,
                   std::vector<PointImpulse>& impulses) {
  SolverReport report;
  // Whether any patch has friction or rolling resistance (their pass is skipped otherwise).
  bool any_friction = false;
  for (const FrictionRow& f : friction)
    any_friction = any_friction || f.mu > 0 || f.rolling_limit > 0;
  std::vector<SweepSize> sizes(static_cast<size_t>(max_threads()));
  for (report.sweeps = 1; report.sweeps <= settings.max_sweeps; ++report.sweeps) {
    std::fill(sizes.begin(), sizes.end(), SweepSize{});
    // Every patch's normal impulses, then every patch's friction.
    by_colour(colours, sizes, [&](int k, SweepSize& size) {
      normal_update(k, rows, friction, patches, impulses, size);
    });
    if (any_friction) {
      by_colour(colours, sizes, [&](int k, SweepSize& size) {
        friction_update(k, friction, patches, points, impulses, size);
      });
    }
    SweepSize total;
    for (const SweepSize& s : sizes) total.add(s.change, s.largest);
    report.change = total.largest > 0 ? total.change / total.largest : 0;
    if (report.change <= settings.tolerance) return report;
  }
  report.sweeps = settings.max_sweeps;
  report.converged = false;
  return report;
}

}  // namespace

// T(y) - T(y0) of the bodies' pseudo velocities: sum of 1/2 (y + y0).W^-1 (y - y0).
Real pseudo_energy_change(const std::vector<BodyResponse>& now, const std::vector<BodyResponse>& start) {
  Real change = 0;
  for (size_t b = 0; b < now.size(); ++b) {
    if (start[b].inverse_mass == 0) continue;
    const Vec3 dv = now[b].velocity - start[b].velocity;
    const Vec3 dw = now[b].angular_velocity - start[b].angular_velocity;
    change += 0.5 * (now[b].velocity + start[b].velocity).dot(dv) / start[b].inverse_mass;
    change += 0.5 * (now[b].angular_velocity + start[b].angular_velocity)
                        .dot(start[b].angular.ldlt().solve(dw));
  }
  return change;
}

Vec3 relative_velocity(const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                       const ContactPoint& c) {
  auto velocity = [&](int body) -> Vec3 {
    if (body < 0) return Vec3::Zero();
    const BodyResponse& r = bodies[body];
    return r.velocity + r.angular_velocity.cross(c.point - centres[body]);
  };
  return velocity(c.body_b) - velocity(c.body_a);
}

namespace {

// The solve for given normal targets; `bodies` ends with the pseudo velocities after it.
// The solve on patches laid out by colour (`colours`: where each colour starts).
SolverReport solve_laid_out(const std::vector<ContactPoint>& points,
                            const std::vector<Real>& targets,
                            const std::vector<BodyResponse>& input,
                            const std::vector<Vec3>& centres, const SolverSettings& settings,
                            const std::vector<int>& colours, std::vector<PatchFriction>& patches,
                            std::vector<PointImpulse>& impulses,
                            std::vector<BodyResponse>& bodies) {
  const size_t n = points.size();
  impulses.resize(n);
  bodies = input;  // pseudo velocities, updated in place
  if (n == 0) return SolverReport{};

  std::vector<NormalRow> rows(n);
  parallel_for(static_cast<long long>(n), 256, [&](long long i) {
    const ContactPoint& c = points[i];
    NormalRow& row = rows[i];
    row.a = side_of(bodies, centres, c.body_a, c.point);
    row.b = side_of(bodies, centres, c.body_b, c.point);
    row.normal = c.normal;
    row.k = c.normal.dot(row.b.response(c.normal, Vec3::Zero()).first +
                         row.a.response(c.normal, Vec3::Zero()).first);
    row.target = targets[i];
  });
  std::vector<FrictionRow> friction(patches.size());
  // Each patch's blocks are its own: shared among threads, the same numbers with any count.
  parallel_for(static_cast<long long>(patches.size()), 64, [&](long long k) {
    PatchFriction& p = patches[k];
    FrictionRow& f = friction[k];
    f.a = side_of(bodies, centres, p.body_a, p.centre);
    f.b = side_of(bodies, centres, p.body_b, p.centre);
    f.start_slip = p.start_slip;
    // K's blocks by probing both sides with unit impulses (the response is linear).
    const Vec3 e[3] = {p.tangent1, p.tangent2, p.normal};
    for (int c = 0; c < 2; ++c) {
      const auto [dvb, dwb] = f.b.response(e[c], Vec3::Zero());
      const auto [dva, dwa] = f.a.response(e[c], Vec3::Zero());
      for (int r = 0; r < 2; ++r) f.k_slip(r, c) = e[r].dot(dvb + dva);
    }
    f.k_twist = p.normal.dot(f.b.response(Vec3::Zero(), p.normal).second +
                             f.a.response(Vec3::Zero(), p.normal).second);
    f.mu = friction_of(settings, p);
    f.rolling_limit = rolling_limit_of(settings, p);
    if (f.rolling_limit > 0) {
      for (int c = 0; c < 2; ++c) {
        const Vec3 dw =
            f.b.response(Vec3::Zero(), e[c]).second + f.a.response(Vec3::Zero(), e[c]).second;
        for (int r = 0; r < 2; ++r) f.k_roll(r, c) = e[r].dot(dw);
      }
      // Neither side turns (walls, fixed bodies): nothing to resist.
      if (!(f.k_roll.determinant() > 0)) f.rolling_limit = 0;
      f.start_roll = Vec2(p.start_roll1, p.start_roll2);
    }
    // The normal block: the change of point i's normal velocity per unit impulse at point j.
    const int m = p.last - p.first;
    f.k_normal.resize(m, m);
    for (int j = 0; j < m; ++j) {
      const NormalRow& at = rows[p.first + j];
      for (int i = 0; i < m; ++i) {
        const NormalRow& row = rows[p.first + i];
        Real v = 0;
        for (const auto& [probe, measure] : {std::pair(at.b, row.b), std::pair(at.a, row.a)}) {
          if (!probe.body) continue;
          const Vec3 dw = probe.body->angular * probe.arm.cross(at.normal);
          v += row.normal.dot(probe.body->inverse_mass * at.normal + dw.cross(measure.arm));
        }
        f.k_normal(i, j) = v;
      }
    }
    BlockMatrix regularised = f.k_normal;
    regularised.diagonal().array() += block_regularisation(f.k_normal);
    f.k_normal_factor.compute(regularised);
    const auto d = f.k_normal_factor.vectorD();
    f.k_normal_well_conditioned = d.minCoeff() > 1e-6 * d.maxCoeff();
  });
  // Warm start: apply the initial guesses, normal and friction.
  bool warm = false;
  for (size_t i = 0; i < n; ++i) {
    warm = warm || impulses[i].normal != 0;
    rows[i].b.apply(impulses[i].normal * rows[i].normal, Vec3::Zero());
    rows[i].a.apply(-impulses[i].normal * rows[i].normal, Vec3::Zero());
  }
  for (size_t k = 0; k < patches.size(); ++k) {
    PatchFriction& p = patches[k];
    if (!(friction[k].mu > 0)) p.t1 = p.t2 = p.twist = 0;
    warm = warm || p.t1 != 0 || p.t2 != 0 || p.twist != 0;
    apply_friction(friction[k], p, Vec3(p.t1, p.t2, p.twist));
    if (!(friction[k].rolling_limit > 0)) p.roll1 = p.roll2 = 0;
    if (p.roll1 != 0 || p.roll2 != 0) {
      warm = true;
      apply_rolling(friction[k], p, Vec2(p.roll1, p.roll2));
    }
  }
  SolverReport report = sweep(rows, friction, patches, points, colours, settings, impulses);
  if (!report.converged && warm && pseudo_energy_change(bodies, input) > 0) {
    std::copy(input.begin(), input.end(), bodies.begin());  // the rows point into `bodies`
    std::fill(impulses.begin(), impulses.end(), PointImpulse{});
    for (PatchFriction& p : patches) p.t1 = p.t2 = p.twist = p.roll1 = p.roll2 = 0;
    const int first_sweeps = report.sweeps;
    report = sweep(rows, friction, patches, points, colours, settings, impulses);
    report.sweeps += first_sweeps;
  }
  return report;
}

// The solve for given normal targets; `bodies` ends with the pseudo velocities after it.
// Patches and their points are laid out by colour for the solve, and the results put back.
SolverReport solve_targets(const std::vector<ContactPoint>& points,
                           const std::vector<Real>& targets,
                           const std::vector<BodyResponse>& input,
                           const std::vector<Vec3>& centres, const SolverSettings& settings,
                           std::vector<PatchFriction>& patches,
                           std::vector<PointImpulse>& impulses,
                           std::vector<BodyResponse>& bodies) {
  impulses.resize(points.size());
  if (!settings.colour_sweeps) {
    // Patch order, one by one: a single serial "colour" holding every patch.
    const std::vector<int> one_by_one = {0, 0, static_cast<int>(patches.size())};
    return solve_laid_out(points, targets, input, centres, settings, one_by_one, patches,
                          impulses, bodies);
  }
  Colouring colouring;
  colour_patches(patches, input, colouring);
  std::vector<ContactPoint> laid_points;
  std::vector<Real> laid_targets;
  std::vector<PointImpulse> laid_impulses;
  std::vector<PatchFriction> laid_patches;
  laid_points.reserve(points.size());
  laid_targets.reserve(points.size());
  laid_impulses.reserve(points.size());
  laid_patches.reserve(patches.size());
  for (int k : colouring.order) {
    PatchFriction p = patches[k];
    p.first = static_cast<int>(laid_points.size());
    for (int i = patches[k].first; i < patches[k].last; ++i) {
      laid_points.push_back(points[i]);
      laid_targets.push_back(targets[i]);
      laid_impulses.push_back(impulses[i]);
    }
    p.last = static_cast<int>(laid_points.size());
    laid_patches.push_back(p);
  }
  const SolverReport report = solve_laid_out(laid_points, laid_targets, input, centres, settings,
                                             colouring.start, laid_patches, laid_impulses, bodies);
  for (size_t j = 0; j < colouring.order.size(); ++j)
    copy_patch_result(laid_patches[j], laid_impulses, patches[colouring.order[j]], impulses);
  return report;
}

}  // namespace

void normal_targets(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                    const std::vector<Real>& start_linear, const SolverSettings& settings,
                    std::vector<Real>& targets, const std::vector<PatchFriction>* patches) {
  // The normal relative velocity required after the step. An impact (approach faster than the
  // threshold) leaves at e times its approach speed; resting contact must not approach; a point
  // already separating may close again as fast as it was opening, no faster. Why the last: over
  // a step the contact impulse does the work dt/2 lambda (u_start + u_after), so a push on a
  // separating point (u_start > 0, u_after = 0) would add energy; with u_after >= -u_start it
  // adds none, and impacts and resting contacts only take energy out.
  //
  // A point still a gap s apart (contact before overlap) must not close past zero. The default
  // integrator moves a body's centre by the mean of the step's start and end velocities (a
  // contact force acts through the step, integrator_default.cpp) but turns it by its end spin,
  // so a point closes by dt (c_lin/2 + c_lin'/2 + c_rot'), c_lin the part of its approach c due
  // to the centres' velocities, c_rot the part due to the spins, ' at the step's end. One that
  // arrives too fast for its gap could only stop at once by bouncing back, so it brakes one
  // step ahead: it asks to end the step approaching at no more than c' = s/dt - c_lin/2, which
  // keeps this step's closure and the next step's, should that one stop it dead, within s
  // (dt (c_lin/2 + c') + dt c_lin'/2 <= s). So a body lands within two steps, at rest, without
  // overlap and without a bounce, also when the landing turns it (a coin falling flat: the
  // far rim stops and the near one would dip), where the margin saw it coming (at least twice
  // a step's motion, contact_margins.hpp). A point still far pushes nothing: its free approach
  // never exceeds what it asks. An impact with restitution (approach above the threshold)
  // instead leaves at e c in the step after which a braked landing could no longer hold it,
  // s < c dt (3 - e)/2: at its full approach speed (braking first would eat the restitution,
  // the known pitfall of speculative contact, so until then it is only kept from closing by
  // more than its gap), from a gap it cannot overrun. Impulses on such points only take the
  // approach out, so they never add energy; separating, the energy rule above caps them.
  const Real dt = settings.time_step;
  targets.resize(points.size());
  const bool per_patch = settings.per_patch && patches;
  for (size_t i = 0; i < points.size(); ++i) {
    const Real e = per_patch ? (*patches)[points[i].patch].restitution : settings.restitution;
    const Real closing = -start[i];
    const Real gap = -points[i].depth;
    if (gap > 0 && dt > 0) {
      Real target;
      if (e > 0 && closing > settings.restitution_threshold) {
        // An impact to come: no braking, only no overlap (closing by exactly the gap at most).
        const bool now = gap < closing * dt * (3 - e) / 2;
        target = now ? e * closing : std::min<Real>(0, closing - 2 * gap / dt);
      } else {
        const Real closing_linear = start_linear.empty() ? closing : -start_linear[i];
        target = std::min<Real>(0, closing_linear / 2 - gap / dt);
      }
      if (closing < 0) target = std::min(target, closing);
      targets[i] = target;
      continue;
    }
    targets[i] = closing > settings.restitution_threshold ? e * closing
                 : closing < 0                            ? closing
                                                          : 0;
  }
}

SolverReport solve_semm(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                        const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                        const SolverSettings& settings, std::vector<PatchFriction>& patches,
                        std::vector<PointImpulse>& impulses) {
  std::vector<Real> targets;
  normal_targets(points, start, {}, settings, targets, &patches);
  std::vector<BodyResponse> after;
  return solve_targets(points, targets, bodies, centres, settings, patches, impulses, after);
}

SolverReport solve_separation(const std::vector<ContactPoint>& points,
                              const std::vector<Real>& targets,
                              const std::vector<BodyResponse>& bodies,
                              const std::vector<Vec3>& centres,
                              std::vector<PatchFriction>& patches,
                              std::vector<PointImpulse>& impulses,
                              std::vector<BodyResponse>& velocities,
                              const SolverSettings& stopping, RowSolverMemory* rows) {
  SolverSettings settings;
  settings.friction = 0;
  settings.tolerance = stopping.tolerance;
  settings.max_sweeps = stopping.max_sweeps;
  settings.colour_sweeps = stopping.colour_sweeps;
  settings.sync = stopping.sync;
  settings.energy_check = false;
  settings.held = stopping.held;
  impulses.assign(points.size(), PointImpulse{});
  for (PatchFriction& p : patches) p.t1 = p.t2 = p.twist = p.roll1 = p.roll2 = 0;
  if (rows) {
    const SolverReport report = solve_semm_rows(points, {}, targets, bodies, centres, settings,
                                                patches, impulses, *rows);
    velocities = bodies;
    for (size_t b = 0; b < bodies.size(); ++b) {
      velocities[b].velocity = rows->slots[b].linear;
      velocities[b].angular_velocity = rows->slots[b].angular;
    }
    return report;
  }
  return solve_targets(points, targets, bodies, centres, settings, patches, impulses,
                       velocities);
}

}  // namespace tem
