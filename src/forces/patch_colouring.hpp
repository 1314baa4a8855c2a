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
  std::vector<int> body_level;      // per body, the level of its last patch (level_patches)
};

// Fills `out` (its vectors reused).
void colour_patches(const std::vector<PatchFriction>& patches,
                    const std::vector<BodyResponse>& bodies, Colouring& out);

// Patch order's own levels, as "colours": a patch's level is one more than the highest level
// among the earlier patches on either of its moving bodies. Patches of one level share no moving
// body, and each body's patches come level after level in patch order, so sweeping level by
// level, with threads sharing a level, reads and writes every body's velocity in exactly the
// sequence of the serial sweep in patch order: the same bits as one thread, patch by patch, at
// any thread count (where colour_patches changes the order, and with it the answer). A settled
// 1,000-coin pile's 2,900 patches fall into about 35 levels, a pour's crash's 960 into 13.
// The last "colour" is empty: no patch is left to go one by one.
void level_patches(const std::vector<PatchFriction>& patches,
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

// Colours (levels) smaller than this go on one thread in sweep_by_colour: a barrier and the
// velocities' move between the cores cost more than sharing a few patches saves (a rotating
// drum's bed: 50 levels of about 10 patches behind two large ones, 1.6 times slower shared).
constexpr int kSharedColour = 32;

// Whether threads sharing the colours save more than they cost: at least half the patches in
// colours of kSharedColour or more. Where they do not (the drum's bed, levels of about 10
// patches), the serial sweep in patch order is faster than any sharing.
inline bool worth_sharing(const std::vector<int>& start) {
  const int n_colours = static_cast<int>(start.size()) - 1;
  int shared = 0;
  for (int c = 0; c + 1 < n_colours; ++c)
    if (start[c + 1] - start[c] >= kSharedColour) shared += start[c + 1] - start[c];
  return 2 * shared >= start.back();
}

// Sweeps as by_colour, again and again, until `done(sizes)` says so after a sweep or `max_sweeps`
// have run; returns how many ran. All of them in one parallel region, the colours (or levels)
// parted by barriers (0.66 us each on the project's machine), where by_colour opens a region per
// colour and sweep and leaves colours under 65 patches to one thread: a pour's crash has 13
// levels of 70 patches on average and up to 16 sub-steps of 20 sweeps a step. (Measured against
// by_colour on the 1,000-coin crash, the two took the same time within the machine's noise.)
// `done` reads every thread's size and must give every thread the same answer; each sweep starts
// with `sizes` cleared.
template <class Update, class Done>
int sweep_by_colour(const std::vector<int>& start, std::vector<SweepSize>& sizes, int max_sweeps,
                    Update&& update, Done&& done) {
  const long long patches = start.back();
  int swept = 0;
#ifdef _OPENMP
  if (patches > 64 && omp_get_max_threads() > 1 && worth_sharing(start)) {
    const int n_colours = static_cast<int>(start.size()) - 1;
#pragma omp parallel
    {
      SweepSize& mine = sizes[thread_index()];
      for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
        mine = SweepSize{};  // the last sweep's sizes were all read before its barrier
        for (int c = 0; c < n_colours;) {
          if (c + 1 < n_colours && start[c + 1] - start[c] >= kSharedColour) {
#pragma omp for schedule(static)
            for (int k = start[c]; k < start[c + 1]; ++k) update(k, mine);
            ++c;
            continue;
          }
          // A run of small colours (and the last, serial one) on one thread, in order: one
          // barrier for all of them. Into that thread's own size: another thread may still be
          // clearing its own at a sweep's start.
          int end = c + 1;
          while (end < n_colours && (end + 1 == n_colours ||
                                     start[end + 1] - start[end] < kSharedColour))
            ++end;
          if (start[end] > start[c]) {
#pragma omp single
            for (int k = start[c]; k < start[end]; ++k) update(k, mine);
          }
          c = end;
        }
        // After the last barrier every size is final; all threads decide alike.
        const bool stop = done(sizes);
#pragma omp barrier
        if (stop || sweep == max_sweeps) {
#pragma omp single nowait
          swept = sweep;
          break;
        }
      }
    }
    return swept;
  }
#endif
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    std::fill(sizes.begin(), sizes.end(), SweepSize{});
    for (long long k = 0; k < patches; ++k) update(static_cast<int>(k), sizes[0]);  // in order
    swept = sweep;
    if (done(sizes)) break;
  }
  return swept;
}

}  // namespace tem
