#include "world/fill.hpp"

#include "world/placement.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>
#include <vector>

namespace tem {
namespace {

constexpr int kAttemptsPerBody = 2000;

// Uniform in [0, 1) from the top 53 bits.
Real unit(std::mt19937_64& rng) { return static_cast<Real>(rng() >> 11) * 0x1.0p-53; }

struct Sphere {
  Vec3 centre;
  Real radius;
};

bool overlap(const Sphere& a, const Sphere& b) {
  return (a.centre - b.centre).squaredNorm() < (a.radius + b.radius) * (a.radius + b.radius);
}

// A uniform grid over the region holding the spheres that reach into each cell. Cells are one
// copy's diameter wide, so a candidate's sphere reaches at most 2 x 2 x 2 of them.
class SphereGrid {
 public:
  SphereGrid(const Vec3& min, const Vec3& max, Real cell) : min_(min), cell_(cell) {
    for (int k = 0; k < 3; ++k)
      cells_[k] = std::max<long long>(1, static_cast<long long>(std::ceil((max[k] - min[k]) / cell)));
    slots_.resize(static_cast<size_t>(cells_[0] * cells_[1] * cells_[2]));
  }

  void insert(const Sphere& s) {
    const int index = static_cast<int>(spheres_.size());
    spheres_.push_back(s);
    for_cells(s, [&](std::vector<int>& slot) { slot.push_back(index); });
  }

  // The spheres that overlap s, by their insertion order.
  void overlapping(const Sphere& s, std::vector<int>& out) {
    out.clear();
    for_cells(s, [&](std::vector<int>& slot) {
      for (int i : slot)
        if (overlap(spheres_[i], s)) out.push_back(i);
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  bool overlaps(const Sphere& s) {
    bool hit = false;
    for_cells(s, [&](std::vector<int>& slot) {
      for (int i : slot) hit = hit || overlap(spheres_[i], s);
    });
    return hit;
  }

 private:
  template <class F>
  void for_cells(const Sphere& s, F&& f) {
    long long lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = static_cast<long long>(std::floor((s.centre[k] - s.radius - min_[k]) / cell_));
      hi[k] = static_cast<long long>(std::floor((s.centre[k] + s.radius - min_[k]) / cell_));
      lo[k] = std::clamp<long long>(lo[k], 0, cells_[k] - 1);
      hi[k] = std::clamp<long long>(hi[k], 0, cells_[k] - 1);
      if (s.centre[k] + s.radius < min_[k] || s.centre[k] - s.radius > min_[k] + cells_[k] * cell_)
        return;  // outside the region: cannot meet a copy
    }
    for (long long z = lo[2]; z <= hi[2]; ++z)
      for (long long y = lo[1]; y <= hi[1]; ++y)
        for (long long x = lo[0]; x <= hi[0]; ++x)
          f(slots_[static_cast<size_t>((z * cells_[1] + y) * cells_[0] + x)]);
  }

  Vec3 min_;
  Real cell_;
  long long cells_[3];
  std::vector<std::vector<int>> slots_;
  std::vector<Sphere> spheres_;
};

}  // namespace

Mat3 uniform_rotation(Real u1, Real u2, Real u3) {
  constexpr Real two_pi = 6.283185307179586;
  const Real a = std::sqrt(1 - u1), b = std::sqrt(u1);
  Quat q(b * std::cos(two_pi * u3), a * std::sin(two_pi * u2), a * std::cos(two_pi * u2),
         b * std::sin(two_pi * u3));
  q.normalize();
  return q.toRotationMatrix();
}

void place_fill(const FillDef& fill, const Body& copy, Model& model) {
  std::unordered_set<std::string> names;
  for (const Body& b : model.bodies) names.insert(b.name);

  // With a size factor, the largest copy sets the room each copy is checked for.
  const Real template_radius = body_size(model, copy);
  const Real largest = fill.body.scale ? fill.body.scale->max : 1;
  const Real room = template_radius * largest;
  const Vec3 lo_all = fill.region_min + Vec3::Constant(room);
  const Vec3 hi_all = fill.region_max - Vec3::Constant(room);
  if (!(lo_all.array() <= hi_all.array()).all())
    throw SceneError(fill.path + ".region",
                     "is too small for one body: each side must be at least the body's "
                     "diameter " + std::to_string(2 * room));

  // Copies of this fill keep clear of each other's bounding spheres; bodies that were there
  // before (a drum, a hopper, an earlier fill) are judged by their blocks (placement.hpp), with
  // their spheres only to find the candidates.
  SphereGrid grid(fill.region_min, fill.region_max, 2 * room);
  SphereGrid before(fill.region_min, fill.region_max, 2 * room);
  const State existing = initial_state(model);
  const size_t existing_count = model.bodies.size();
  for (size_t i = 0; i < existing_count; ++i)
    before.insert({existing.bodies[i].x, body_size(model, static_cast<int>(i))});
  std::vector<int> near;

  std::mt19937_64 rng(fill.seed);
  model.bodies.reserve(model.bodies.size() + static_cast<size_t>(fill.count));
  for (int n = 0; n < fill.count; ++n) {
    Body body = copy;
    Real radius = template_radius;
    if (fill.body.scale) {
      const Real factor = fill.body.scale->min + unit(rng) * (fill.body.scale->max - fill.body.scale->min);
      if (factor != 1) {
        body = build_body(fill.body, model, factor);
        radius = body_size(model, body);
      }
    }
    const Vec3 lo = fill.region_min + Vec3::Constant(radius);
    const Vec3 hi = fill.region_max - Vec3::Constant(radius);
    body.name = fill.name + "_" + std::to_string(n);
    if (!names.insert(body.name).second)
      throw SceneError(fill.path + ".name", "makes the body name '" + body.name +
                                                "', which another body already has");
    bool placed = false;
    for (int attempt = 0; attempt < kAttemptsPerBody && !placed; ++attempt) {
      Vec3 centre;
      for (int k = 0; k < 3; ++k) centre[k] = lo[k] + unit(rng) * (hi[k] - lo[k]);
      if (grid.overlaps({centre, radius})) continue;
      before.overlapping({centre, radius}, near);
      bool clear = true;
      for (int i : near)
        clear = clear && sphere_clear_of_body(model, model.bodies[i], existing.bodies[i], centre, radius);
      if (!clear) continue;
      const Real u1 = unit(rng), u2 = unit(rng), u3 = unit(rng);
      body.start_rotation = uniform_rotation(u1, u2, u3);
      // The centre of mass goes to `centre`; the scene's frame origin sits origin_offset from it.
      body.start_position = centre + body.start_rotation * body.origin_offset;
      grid.insert({centre, radius});
      placed = true;
    }
    if (!placed)
      throw SceneError(fill.path + ".count",
                       "only " + std::to_string(n) + " of " + std::to_string(fill.count) +
                           " bodies fit in the region without touching (each needs a free "
                           "sphere of radius " + std::to_string(radius) +
                           "); enlarge the region or lower the count");
    model.bodies.push_back(std::move(body));
  }
}

}  // namespace tem
