#include "distributed/contact_memory.hpp"

#include <algorithm>

namespace tem::distributed {
std::vector<MemoryPatch> memory_patches(const ContactForces& f) {
  std::vector<MemoryPatch> out;
  for (size_t i = 0; i < f.points.size();) {
    const int k = f.points[i].patch;
    MemoryPatch p;
    if (k >= 0 && static_cast<size_t>(k) < f.friction.size()) p.friction = f.friction[k];
    p.friction.body_a = f.points[i].body_a;
    p.friction.body_b = f.points[i].body_b;
    p.friction.wall = f.points[i].wall;
    for (; i < f.points.size() && f.points[i].patch == k; ++i) {
      p.points.push_back(f.points[i]);
      p.impulses.push_back(i < f.impulses.size() ? f.impulses[i] : PointImpulse{});
    }
    out.push_back(std::move(p));
  }
  return out;
}

void set_memory_patches(std::vector<MemoryPatch> patches, ContactForces& f) {
  std::stable_sort(patches.begin(), patches.end(), [](const MemoryPatch& x, const MemoryPatch& y) {
    return pair_key(x.friction) < pair_key(y.friction);
  });
  f.points.clear();
  f.impulses.clear();
  f.friction.clear();
  for (MemoryPatch& p : patches) {
    const int k = static_cast<int>(f.friction.size());
    p.friction.first = static_cast<int>(f.points.size());
    for (size_t i = 0; i < p.points.size(); ++i) {
      p.points[i].patch = k;
      f.points.push_back(p.points[i]);
      f.impulses.push_back(p.impulses[i]);
    }
    p.friction.last = static_cast<int>(f.points.size());
    f.friction.push_back(p.friction);
  }
}

void pack(Packer& out, const MemoryPatch& p) {
  out.put(p.friction);
  out.put(static_cast<double>(p.points.size()));
  for (size_t i = 0; i < p.points.size(); ++i) {
    out.put(p.points[i]);
    out.put(p.impulses[i].normal);
  }
}

MemoryPatch unpack_memory_patch(Unpacker& in) {
  MemoryPatch p;
  p.friction = in.friction();
  const int n = in.integer();
  for (int i = 0; i < n; ++i) {
    p.points.push_back(in.point());
    PointImpulse j;
    j.normal = in.number();
    p.impulses.push_back(j);
  }
  return p;
}

void sort_springs(std::vector<PenaltySpring>& springs) {
  std::stable_sort(
      springs.begin(), springs.end(),
      [](const PenaltySpring& p, const PenaltySpring& q) { return pair_key(p) < pair_key(q); });
}

}  // namespace tem::distributed
