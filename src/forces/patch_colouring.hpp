// The order in which the contact solvers' Gauss-Seidel sweeps visit the patches, and how the
// threads share them (semm.cpp, semm_rows.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "forces/body_response.hpp"
#include "forces/semm.hpp"
#include "support/parallel.hpp"

namespace tem {

// The order in which Gauss-Seidel visits the patches: by colour, so that the patches of one
// colour share no moving body. Their updates then read and write disjoint bodies, so within a
// colour they can go in any order, or on several threads, and give the same bits: the answer
// depends on the colouring, never on the thread count. Greedy, in patch order: a patch takes the
// lowest colour neither of its bodies has yet; the few that find none of 64 go last, one by one.
// The solver works on the patches and points laid out in this order (solve_targets), so that
// each colour's rows lie together in memory.
constexpr int kColours = 64;
// Slabs across the pile that order the patches of one colour (patch_colouring.cpp).
constexpr int kSlabs = 64;

struct Colouring {
  std::vector<int> order;  // patch indices, colour by colour, in patch order within a colour
  std::vector<int> start;  // colour c is order[start[c], start[c + 1]); the last one is serial
  // Scratch kept between steps so that colouring a running pile allocates nothing.
  std::vector<std::uint64_t> used;  // per body, the colours its patches have taken
  std::vector<int> colour, key;     // per patch: its colour, and its colour and slab
  std::vector<int> count, next;     // per colour and slab
};

// Fills `out` (its vectors reused).
void colour_patches(const std::vector<PatchFriction>& patches,
                    const std::vector<BodyResponse>& bodies, Colouring& out);

// The largest impulse change and the largest impulse of a sweep, kept per thread (the maximum
// does not depend on the order it is taken in). A cache line of its own: every patch's update
// writes it, and two threads' sizes in one line made colour sweeps on two threads slower than
// on one (the line went back and forth between the cores at every patch).
struct alignas(64) SweepSize {
  Real change = 0, largest = 0;
  void add(Real c, Real l) {
    change = std::max(change, c);
    largest = std::max(largest, l);
  }
};

// Runs `update(k, size)` on every patch, colour after colour (the patches laid out by colour:
// colour c is [start[c], start[c + 1])); a colour's patches are shared among the threads when
// there are enough of them to be worth a parallel region.
template <class Update>
void by_colour(const std::vector<int>& start, std::vector<SweepSize>& sizes, Update&& update) {
  const int n_colours = static_cast<int>(start.size()) - 1;
  for (int c = 0; c < n_colours; ++c) {
    const int first = start[c], count = start[c + 1] - first;
    if (c == n_colours - 1) {  // patches that found no colour: one by one
      for (int k = first; k < first + count; ++k) update(k, sizes[0]);
      continue;
    }
    parallel_for(count, 64, [&](long long i) {
      update(first + static_cast<int>(i), sizes[thread_index()]);
    });
  }
}

}  // namespace tem
