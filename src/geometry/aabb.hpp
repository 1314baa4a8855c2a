// An axis-aligned bounding box: the broad phase's bounds of a block, a domain's bounds of its
// bodies, and the approximate cutter's first test of whether two hulls can meet. Always the
// cheap test before an exact one.
#pragma once

#include <limits>
#include <vector>

#include "tem/types.hpp"

namespace tem {

struct Aabb {
  Vec3 min, max;

  // The box that holds nothing: whatever is added to it becomes the box.
  static Aabb empty() {
    const Real inf = std::numeric_limits<Real>::infinity();
    return {Vec3::Constant(inf), Vec3::Constant(-inf)};
  }
  static Aabb around(const std::vector<Vec3>& points) {
    Aabb box = empty();
    for (const Vec3& p : points) box.add(p);
    return box;
  }
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const Aabb& o) {
    min = min.cwiseMin(o.min);
    max = max.cwiseMax(o.max);
  }
  bool overlaps(const Aabb& o) const {
    return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
  }
  // Whether the boxes overlap or come within `gap` of each other along every axis.
  bool within(const Aabb& o, Real gap) const {
    return (min.array() <= o.max.array() + gap).all() && (o.min.array() <= max.array() + gap).all();
  }
};

}  // namespace tem
