#include "contact/initial_overlap.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>

#include "contact/detect_contacts.hpp"

namespace tem {
namespace {

std::string wall_name(const Model& model, int wall) {
  if (model.scene.container && wall < 6) {
    static const char* const faces[6] = {"x min", "x max", "y min", "y max", "z min", "z max"};
    return std::string("the container's ") + faces[wall] + " face";
  }
  const int listed = wall - (model.scene.container ? 6 : 0);
  return "walls[" + std::to_string(listed) + "]";
}

}  // namespace

std::vector<InitialOverlap> deep_initial_overlaps(const Model& model, Real fraction) {
  const State state = initial_state(model);
  ContactWorkspace workspace;
  std::vector<ContactPatch> patches;
  detect_contacts(model, state, patch_variant(model.scene), workspace, patches);

  std::map<std::tuple<int, int, int>, InitialOverlap> deepest;
  for (const ContactPatch& p : patches) {
    Real size = body_size(model, p.body_a);
    if (p.body_b >= 0) size = std::min(size, body_size(model, p.body_b));
    if (p.depth <= fraction * size) continue;
    InitialOverlap& o = deepest[{p.body_a, p.body_b, p.wall}];
    if (p.depth > o.depth) o = {p.body_a, p.body_b, p.wall, p.depth, p.depth / size};
  }
  std::vector<InitialOverlap> out;
  for (const auto& [key, overlap] : deepest) out.push_back(overlap);
  std::stable_sort(out.begin(), out.end(), [](const InitialOverlap& a, const InitialOverlap& b) {
    return a.depth > b.depth;
  });
  return out;
}

std::string describe(const Model& model, const InitialOverlap& o) {
  char amount[96];
  std::snprintf(amount, sizeof amount, " overlap by %.4g (%.3g%% of the %s size) at the start",
                o.depth, 100 * o.relative, o.body_b >= 0 ? "smaller one's" : "body's");
  const std::string a = "'" + model.bodies[o.body_a].name + "'";
  if (o.body_b >= 0) return "bodies " + a + " and '" + model.bodies[o.body_b].name + "'" + amount;
  return "body " + a + " and " + wall_name(model, o.wall) + amount;
}

}  // namespace tem
