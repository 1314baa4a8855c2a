#include "forces/warm_start.hpp"

#include <algorithm>
#include <array>

#include "support/parallel.hpp"

namespace tem {

void warm_start(const std::vector<ContactPoint>& previous,
                const std::vector<PointImpulse>& previous_impulses,
                const std::vector<ContactPoint>& points, const std::vector<Real>& radius,
                std::vector<PointImpulse>& impulses) {
  impulses.assign(points.size(), PointImpulse{});
  // The runs of one pair in each list; patches come sorted by pair, so the runs are in the same
  // order in both and one pass pairs them up. The matching within each run is the cost, and
  // each run's is its own, so the runs are then shared among the threads.
  std::vector<std::array<size_t, 4>> runs;  // first, last, old_first, old_last
  size_t old_first = 0;
  for (size_t first = 0; first < points.size();) {
    size_t last = first;
    while (last < points.size() && pair_key(points[last]) == pair_key(points[first])) ++last;
    while (old_first < previous.size() && pair_key(previous[old_first]) < pair_key(points[first]))
      ++old_first;
    size_t old_last = old_first;
    while (old_last < previous.size() && pair_key(previous[old_last]) == pair_key(points[first]))
      ++old_last;
    if (old_last > old_first) runs.push_back({first, last, old_first, old_last});
    first = last;
  }
  parallel_for(static_cast<long long>(runs.size()), 64, [&](long long run) {
    const auto [first, last, old_first, old_last] = runs[static_cast<size_t>(run)];
    const Real r = radius[points[first].body_a];
    for (size_t i = first; i < last; ++i) {
      size_t best = old_last;
      Real best_distance = r;
      for (size_t k = old_first; k < old_last; ++k) {
        const Real d = (previous[k].point - points[i].point).norm();
        if (d < best_distance) {
          best_distance = d;
          best = k;
        }
      }
      if (best == old_last) continue;
      // The old normal impulse, kept where the normal has not turned away.
      const Real along = previous[best].normal.dot(points[i].normal);
      impulses[i].normal = std::max<Real>(0, previous_impulses[best].normal * along);
    }
  });
}

void warm_start_friction(const std::vector<PatchFriction>& previous,
                         const std::vector<Real>& radius, std::vector<PatchFriction>& patches) {
  size_t old_first = 0;
  for (PatchFriction& p : patches) {
    p.t1 = p.t2 = p.twist = p.roll1 = p.roll2 = 0;
    while (old_first < previous.size() && pair_key(previous[old_first]) < pair_key(p)) ++old_first;
    Real best_distance = radius[p.body_a];
    const PatchFriction* best = nullptr;
    for (size_t k = old_first; k < previous.size() && pair_key(previous[k]) == pair_key(p); ++k) {
      const Real d = (previous[k].centre - p.centre).norm();
      if (d < best_distance) {
        best_distance = d;
        best = &previous[k];
      }
    }
    if (!best) continue;
    const Vec3 t = best->t1 * best->tangent1 + best->t2 * best->tangent2;
    p.t1 = t.dot(p.tangent1);
    p.t2 = t.dot(p.tangent2);
    p.twist = best->twist * best->normal.dot(p.normal);
    if (best->roll1 != 0 || best->roll2 != 0) {  // rolling resistance: as the tangential impulse
      const Vec3 h = best->roll1 * best->tangent1 + best->roll2 * best->tangent2;
      p.roll1 = h.dot(p.tangent1);
      p.roll2 = h.dot(p.tangent2);
    }
  }
}

}  // namespace tem
