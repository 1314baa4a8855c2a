#include "forces/patch_colouring.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

namespace tem {

void colour_patches(const std::vector<PatchFriction>& patches,
                    const std::vector<BodyResponse>& bodies, Colouring& out) {
  std::vector<std::uint64_t>& used = out.used;
  used.assign(bodies.size(), 0);
  auto moving = [&](int b) { return b >= 0 && bodies[b].inverse_mass > 0 ? b : -1; };
  std::vector<int>& colour = out.colour;
  colour.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k) {
    const int a = moving(patches[k].body_a), b = moving(patches[k].body_b);
    const std::uint64_t taken = (a >= 0 ? used[a] : 0) | (b >= 0 ? used[b] : 0);
    const int c = ~taken == 0 ? kColours : std::countr_zero(~taken);
    if (c < kColours) {
      if (a >= 0) used[a] |= std::uint64_t{1} << c;
      if (b >= 0) used[b] |= std::uint64_t{1} << c;
    }
    colour[k] = c;
  }
  // Within a colour the patches go in slabs across the pile (their centres along its longest
  // side, in patch order within a slab), so that the threads sharing a colour take neighbouring
  // regions of the pile, and each body stays with one thread from colour to colour instead of
  // its velocities moving between the cores (for the results the order within a colour does
  // not matter: its patches share no moving body). The patches that found no colour keep patch
  // order, their Gauss-Seidel order.
  Vec3 low = Vec3::Constant(std::numeric_limits<Real>::infinity()), high = -low;
  for (const PatchFriction& p : patches) {
    low = low.cwiseMin(p.centre);
    high = high.cwiseMax(p.centre);
  }
  int axis = 0;
  if (!patches.empty()) (high - low).maxCoeff(&axis);
  const Real width = patches.empty() ? 0 : high[axis] - low[axis];
  std::vector<int>& key = out.key;
  key.resize(patches.size());
  std::vector<int>& count = out.count;
  count.assign(static_cast<size_t>((kColours + 1) * kSlabs), 0);
  for (size_t k = 0; k < patches.size(); ++k) {
    int slab = 0;
    if (colour[k] < kColours && width > 0)
      slab = std::min(kSlabs - 1,
                      static_cast<int>(kSlabs * (patches[k].centre[axis] - low[axis]) / width));
    key[k] = colour[k] * kSlabs + slab;
    ++count[static_cast<size_t>(key[k])];
  }
  out.start.assign(kColours + 2, 0);
  std::vector<int>& next = out.next;
  next.assign(count.size(), 0);
  for (size_t i = 1; i < count.size(); ++i) next[i] = next[i - 1] + count[i - 1];
  for (int c = 0; c <= kColours; ++c) out.start[c] = next[static_cast<size_t>(c * kSlabs)];
  out.start[kColours + 1] = static_cast<int>(patches.size());
  out.order.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k)
    out.order[static_cast<size_t>(next[static_cast<size_t>(key[k])]++)] = static_cast<int>(k);
}

void level_patches(const std::vector<PatchFriction>& patches,
                   const std::vector<BodyResponse>& bodies, Colouring& out) {
  // Bodies that impulses move; walls, fixed and driven bodies are only read by the sweeps.
  auto moving = [&](int b) { return b >= 0 && bodies[b].inverse_mass > 0 ? b : -1; };
  std::vector<int>& body_level = out.body_level;
  body_level.assign(bodies.size(), -1);
  std::vector<int>& level = out.colour;
  level.resize(patches.size());
  int levels = 0;
  for (size_t k = 0; k < patches.size(); ++k) {
    const int a = moving(patches[k].body_a), b = moving(patches[k].body_b);
    const int l = 1 + std::max(a >= 0 ? body_level[a] : -1, b >= 0 ? body_level[b] : -1);
    if (a >= 0) body_level[a] = l;
    if (b >= 0) body_level[b] = l;
    level[k] = l;
    levels = std::max(levels, l + 1);
  }
  // Counting sort by level, patch order kept within a level.
  std::vector<int>& start = out.start;
  start.assign(static_cast<size_t>(levels) + 2, 0);
  for (size_t k = 0; k < patches.size(); ++k) ++start[static_cast<size_t>(level[k]) + 1];
  for (int l = 0; l < levels; ++l) start[l + 1] += start[l];
  start[levels + 1] = start[levels];  // the empty serial "colour"
  std::vector<int>& next = out.next;
  next.assign(start.begin(), start.end() - 1);
  out.order.resize(patches.size());
  for (size_t k = 0; k < patches.size(); ++k)
    out.order[static_cast<size_t>(next[static_cast<size_t>(level[k])]++)] = static_cast<int>(k);
}

}  // namespace tem
