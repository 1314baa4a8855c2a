#include "forces/patch_colouring.hpp"

#include <array>
#include <bit>
#include <cstdint>

namespace tem {

void colour_patches(const std::vector<PatchFriction>& patches,
                    const std::vector<BodyResponse>& bodies, Colouring& out) {
  std::vector<std::uint64_t>& used = out.used;
  used.assign(bodies.size(), 0);
  auto moving = [&](int b) { return b >= 0 && bodies[b].inverse_mass > 0 ? b : -1; };
  std::vector<int>& colour = out.colour;
  colour.resize(patches.size());
  std::array<int, kColours + 1> count{};
  for (size_t k = 0; k < patches.size(); ++k) {
    const int a = moving(patches[k].body_a), b = moving(patches[k].body_b);
    const std::uint64_t taken = (a >= 0 ? used[a] : 0) | (b >= 0 ? used[b] : 0);
    const int c = ~taken == 0 ? kColours : std::countr_zero(~taken);
    if (c < kColours) {
      if (a >= 0) used[a] |= std::uint64_t{1} << c;
      if (b >= 0) used[b] |= std::uint64_t{1} << c;
    }
    colour[k] = c;
    ++count[c];
  }
  out.start.assign(kColours + 2, 0);
  for (int c = 0; c <= kColours; ++c) out.start[c + 1] = out.start[c] + count[c];
  out.order.resize(patches.size());
  std::array<int, kColours + 1> next{};
  for (int c = 0; c <= kColours; ++c) next[c] = out.start[c];
  for (size_t k = 0; k < patches.size(); ++k) out.order[next[colour[k]]++] = static_cast<int>(k);
}

}  // namespace tem
