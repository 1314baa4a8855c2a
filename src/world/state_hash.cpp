#include "world/state_hash.hpp"

#include <cstdio>

#include "support/fnv1a.hpp"

namespace tem {
namespace {

void mix(std::uint64_t& h, Real value) {
  value += 0.0;  // -0 and +0 are the same state
  fnv1a_mix(h, &value, sizeof value);
}

}  // namespace

std::uint64_t state_hash(const State& state) {
  std::uint64_t h = kFnv1aOffset;
  const long long step = state.step;
  fnv1a_mix(h, &step, sizeof step);
  for (const BodyState& b : state.bodies) {
    for (int k = 0; k < 3; ++k) mix(h, b.x[k]);
    for (int k = 0; k < 3; ++k) mix(h, b.v[k]);
    for (int k = 0; k < 9; ++k) mix(h, b.g(k));
    for (int k = 0; k < 3; ++k) mix(h, b.omega[k]);
    for (int k = 0; k < 3; ++k) mix(h, b.prev_torque[k]);
  }
  // Who the bodies are, once bodies have come or gone (a scene without processes keeps the
  // hash it always had).
  bool renumbered = false;
  for (size_t i = 0; i < state.tags.size() && !renumbered; ++i)
    renumbered = state.tags[i].id != static_cast<long long>(i) || state.tags[i].inlet >= 0;
  if (renumbered) {
    for (const BodyTag& t : state.tags) {
      fnv1a_mix(h, &t.id, sizeof t.id);
      mix(h, t.scale);
    }
  }
  return h;
}

std::string hash_hex(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace tem
