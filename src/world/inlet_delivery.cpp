#include "world/inlet_delivery.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "world/placement.hpp"

namespace tem {
namespace {

// Trial centres per axis of the grid that looks for room in an inlet's region.
constexpr int kTrialsPerAxis = 6;

// Whether a body stays where it starts for the whole run (fixed, not driven, never removed):
// what such bodies cover, no copy can ever be placed in.
bool stays(const Body& body) {
  return body.fixed && !body.motion && !std::isfinite(body.removed_at);
}

// The box of centres the placement draws from (the region less the copy's radius on each side).
RegionDef centre_box(const InletDef& inlet, Real radius) {
  return {inlet.region.min + Vec3::Constant(radius), inlet.region.max - Vec3::Constant(radius)};
}

Real volume(const RegionDef& r) {
  const Vec3 side = (r.max - r.min).cwiseMax(Vec3::Zero());
  return side.prod();
}

// The path of an inlet's region or of the inlet, for messages.
std::string region_path(const InletDef& inlet) { return inlet.path + ".region"; }

// Whether any trial centre of a grid over the region has room for the smallest copy among the
// walls and the bodies that stay; the bodies that block every trial otherwise.
bool room_somewhere(const Model& model, const InletDef& inlet, Real radius,
                    std::vector<std::string>* blocking) {
  const State start = initial_state(model);
  const RegionDef box = centre_box(inlet, radius);
  std::vector<char> blocks(model.bodies.size(), 0);
  for (int i = 0; i < kTrialsPerAxis; ++i)
    for (int j = 0; j < kTrialsPerAxis; ++j)
      for (int k = 0; k < kTrialsPerAxis; ++k) {
        const Vec3 f = (Vec3(i, j, k) + Vec3::Constant(0.5)) / kTrialsPerAxis;
        const Vec3 centre = box.min + f.cwiseProduct(box.max - box.min);
        bool clear = true;
        for (const Wall& wall : model.walls)
          if (!std::isfinite(wall.removed_at) && wall.normal.dot(centre - wall.point) < radius)
            clear = false;
        for (size_t b = 0; b < model.bodies.size(); ++b) {
          if (!stays(model.bodies[b])) continue;
          if (!sphere_clear_of_body(model, model.bodies[b], start.bodies[b], centre, radius)) {
            blocks[b] = 1;
            clear = false;
          }
        }
        if (clear) return true;
      }
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (blocks[b]) blocking->push_back(model.bodies[b].name);
  return false;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < names.size() && i < 3; ++i) list += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > 3) list += " and " + std::to_string(names.size() - 3) + " more";
  return list;
}

}  // namespace

long long copies_due(const InletDef& inlet, Real t) {
  if (t < inlet.start) return 0;
  const Real due = std::floor((t - inlet.start) * inlet.rate * (1 + 1e-12)) + 1;
  return std::min<long long>(inlet.count, static_cast<long long>(std::min<Real>(due, 1e18)));
}

std::vector<std::string> inlet_warnings(const Model& model) {
  std::vector<std::string> warnings;
  const SceneDef& scene = model.scene;
  for (size_t j = 0; j < scene.inlets.size(); ++j) {
    const InletDef& inlet = scene.inlets[j];
    std::ostringstream w;
    // Copies are placed for the state each step leaves, the last at `duration`.
    const long long due = copies_due(inlet, scene.duration);
    if (due == 0) {
      w << inlet.path << ".start: " << inlet.start << " s is after the run's end (duration "
        << scene.duration << " s): the inlet places none of its " << inlet.count
        << " copies in this run";
      warnings.push_back(w.str());
      continue;
    }
    if (due < inlet.count) {
      w << inlet.path << ": only " << due << " of its " << inlet.count
        << " copies fall due before the run ends (" << inlet.rate << " per s from " << inlet.start
        << " s, duration " << scene.duration << " s); the others would come in a longer run";
      warnings.push_back(w.str());
      w.str("");
    }
    const Real smallest = inlet.body.scale ? inlet.body.scale->min : 1;
    const Real radius = smallest * body_size(model, model.inlet_templates[j]);
    std::vector<std::string> blocking;
    if (!room_somewhere(model, inlet, radius, &blocking)) {
      w << region_path(inlet) << ": none of " << kTrialsPerAxis * kTrialsPerAxis * kTrialsPerAxis
        << " places spread over the region has room for a copy (a sphere of radius " << radius
        << " clear of the walls"
        << (blocking.empty() ? std::string() : " and of fixed " + quoted_list(blocking))
        << "): the inlet will likely place none of its copies";
      warnings.push_back(w.str());
      w.str("");
    }
    // Copies whose centre starts inside an outlet are removed by the next step's removal.
    const RegionDef box = centre_box(inlet, radius);
    for (size_t k = 0; k < scene.outlets.size(); ++k) {
      const RegionDef& out = scene.outlets[k].region;
      const bool inside_all = (box.min.array() >= out.min.array()).all() &&
                              (box.max.array() <= out.max.array()).all();
      const RegionDef common{box.min.cwiseMax(out.min), box.max.cwiseMin(out.max)};
      // A region one copy wide has a centre box of no volume: then only "all inside" is told.
      const Real share = inside_all ? 1 : volume(box) > 0 ? volume(common) / volume(box) : 0;
      if (share <= 0) continue;
      w << region_path(inlet) << ": "
        << (inside_all ? std::string("every copy is")
                       : std::to_string(std::max(1L, std::lround(100 * share))) +
                             " % of the places a copy can take are")
        << " inside " << scene.outlets[k].path
        << ".region: such copies are removed the step after they are placed";
      warnings.push_back(w.str());
      w.str("");
    }
  }
  return warnings;
}

}  // namespace tem
