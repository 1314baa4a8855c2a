// The sweeps' order by colours (patch_colouring.hpp): a colour's patches share no moving body,
// so threads may share it; within a colour they go in slabs across the pile, so that each thread
// keeps to one region; the patches that found no colour keep patch order. And patch order's
// levels (level_patches), which threads share with the serial sweep's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "forces/patch_colouring.hpp"

namespace tem {
namespace test_patch_colouring {

// A pile-like contact graph: `bodies` bodies at random places in a box 8 x 3 x 2 long along x,
// each patch between a body and one of its near neighbours (or the floor, body -1), its centre
// between the two; bodies below 4 are fixed (inverse mass 0), as walls' slots are.
struct Graph {
  std::vector<BodyResponse> bodies;
  std::vector<PatchFriction> patches;
};

Graph random_graph(int bodies, int patches, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<Real> unit(0, 1);
  Graph g;
  std::vector<Vec3> at(static_cast<size_t>(bodies));
  for (int b = 0; b < bodies; ++b) {
    at[b] = Vec3(8 * unit(random), 3 * unit(random), 2 * unit(random));
    BodyResponse r;
    r.inverse_mass = b < 4 ? 0 : 1;
    g.bodies.push_back(r);
  }
  std::uniform_int_distribution<int> any(0, bodies - 1);
  while (static_cast<int>(g.patches.size()) < patches) {
    PatchFriction p;
    p.body_b = any(random);
    p.body_a = unit(random) < 0.1 ? -1 : any(random);
    if (p.body_a == p.body_b) continue;
    if (p.body_a >= 0 && (at[p.body_a] - at[p.body_b]).norm() > 0.8) continue;
    p.centre = p.body_a >= 0 ? Vec3((at[p.body_a] + at[p.body_b]) / 2) : at[p.body_b];
    g.patches.push_back(p);
  }
  return g;
}

// More patches on one body than there are colours: the rest go last, in patch order.
TEST(PatchColouring, ColoursShareNoMovingBodyAndGoInSlabs) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Graph g = random_graph(400, 2500, seed);
    for (int k = 0; k < kColours + 10; ++k) {  // a body that touches 74 patches
      PatchFriction p;
      p.body_a = 5;
      p.body_b = 6 + k;
      p.centre = Vec3(0.1 * k, 1, 1);
      g.patches.push_back(p);
    }
    Colouring c;
    colour_patches(g.patches, g.bodies, c);
    const int n = static_cast<int>(g.patches.size());
    ASSERT_EQ(static_cast<int>(c.order.size()), n);
    ASSERT_EQ(static_cast<int>(c.start.size()), kColours + 2);
    EXPECT_EQ(c.start.front(), 0);
    EXPECT_EQ(c.start.back(), n);
    std::vector<int> sorted = c.order;
    std::sort(sorted.begin(), sorted.end());
    for (int k = 0; k < n; ++k) ASSERT_EQ(sorted[k], k) << "every patch once";

    // Slabs along x (the graph's longest side): 1/64 of the centres' extent each, the centres'
    // slabs never going back within a colour, and patch order within a slab.
    Real low = g.patches[0].centre.x(), high = low;
    for (const PatchFriction& p : g.patches) {
      low = std::min(low, p.centre.x());
      high = std::max(high, p.centre.x());
    }
    auto slab_of = [&](const PatchFriction& p) {
      return std::min(kSlabs - 1, static_cast<int>(kSlabs * (p.centre.x() - low) / (high - low)));
    };
    int used_colours = 0;
    for (int colour = 0; colour < kColours; ++colour) {
      std::set<int> touched;
      int last_slab = -1, last_patch = -1;
      if (c.start[colour + 1] > c.start[colour]) ++used_colours;
      for (int i = c.start[colour]; i < c.start[colour + 1]; ++i) {
        const PatchFriction& p = g.patches[c.order[i]];
        for (int b : {p.body_a, p.body_b}) {
          if (b >= 0 && g.bodies[b].inverse_mass > 0) {
            EXPECT_TRUE(touched.insert(b).second) << "body " << b << " twice in colour " << colour;
          }
        }
        const int slab = slab_of(p);
        EXPECT_GE(slab, last_slab) << colour;
        if (slab == last_slab) {
          EXPECT_GT(c.order[i], last_patch);
        }
        last_slab = slab;
        last_patch = c.order[i];
      }
    }
    EXPECT_GT(used_colours, 8);
    // The body with 74 patches: 64 of them coloured, 10 left over, one by one in patch order.
    const int left = c.start[kColours + 1] - c.start[kColours];
    EXPECT_GE(left, 10);
    for (int i = c.start[kColours] + 1; i < c.start[kColours + 1]; ++i)
      EXPECT_LT(c.order[i - 1], c.order[i]);
  }
}

// Slabs are thin enough that each of two threads, taking one half of a colour, keeps mostly to
// its own bodies from colour to colour: the bodies that both threads update in one sweep are a
// small share of those updated at all (in patch order within a colour, about half would be).
TEST(PatchColouring, TwoHalvesOfEachColourKeepMostlyApart) {
  const Graph g = random_graph(1000, 5000, 7);
  Colouring c;
  colour_patches(g.patches, g.bodies, c);
  std::vector<int> half_of(g.bodies.size(), -1);
  int shared = 0, updated = 0;
  std::vector<bool> is_shared(g.bodies.size(), false);
  for (int colour = 0; colour < kColours; ++colour) {
    const int first = c.start[colour], count = c.start[colour + 1] - first;
    for (int i = 0; i < count; ++i) {
      const PatchFriction& p = g.patches[c.order[first + i]];
      const int half = 2 * i < count ? 0 : 1;
      for (int b : {p.body_a, p.body_b}) {
        if (b < 0 || g.bodies[b].inverse_mass == 0) continue;
        if (half_of[b] < 0) {
          half_of[b] = half;
          ++updated;
        } else if (half_of[b] != half && !is_shared[b]) {
          is_shared[b] = true;
          ++shared;
        }
      }
    }
  }
  EXPECT_GT(updated, 900);
  EXPECT_LT(shared, updated / 5) << shared << " of " << updated;
}

// Level by level is patch order for every body: a level's patches share no moving body, each
// moving body meets its patches in patch order, and each patch sits at the lowest level that
// allows it (one above its bodies' earlier patches), so that levels are few. Fixed bodies and
// walls (inverse mass 0, body -1), only read by the sweeps, tie nothing: 37 patches on body 5
// take 37 levels at least, the 37 on fixed body 2 none.
TEST(PatchColouring, LevelsKeepEveryBodysPatchesInPatchOrder) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Graph g = random_graph(400, 2500, seed);
    for (int k = 0; k < 74; ++k) {
      PatchFriction p;
      p.body_a = k % 2 ? 5 : 2;
      p.body_b = 6 + k;
      g.patches.push_back(p);
    }
    Colouring c;
    level_patches(g.patches, g.bodies, c);
    const int n = static_cast<int>(g.patches.size());
    ASSERT_EQ(static_cast<int>(c.order.size()), n);
    ASSERT_GE(c.start.size(), 3u);
    EXPECT_EQ(c.start.front(), 0);
    EXPECT_EQ(c.start.back(), n);
    const int levels = static_cast<int>(c.start.size()) - 2;
    EXPECT_EQ(c.start[levels], c.start[levels + 1]) << "nothing left one by one";
    std::vector<int> level_of(n, -1);
    for (int l = 0; l < levels; ++l) {
      EXPECT_GT(c.start[l + 1], c.start[l]) << "level " << l << " empty";
      std::set<int> touched;
      for (int i = c.start[l]; i < c.start[l + 1]; ++i) {
        if (i > c.start[l]) {
          EXPECT_LT(c.order[i - 1], c.order[i]) << "patch order in a level";
        }
        level_of[c.order[i]] = l;
        const PatchFriction& p = g.patches[c.order[i]];
        for (int b : {p.body_a, p.body_b}) {
          if (b >= 0 && g.bodies[b].inverse_mass > 0) {
            EXPECT_TRUE(touched.insert(b).second) << "body " << b << " twice in level " << l;
          }
        }
      }
    }
    // Each patch's level from the patches before it, in patch order.
    std::vector<int> last(g.bodies.size(), -1);
    for (int k = 0; k < n; ++k) {
      ASSERT_GE(level_of[k], 0) << "patch " << k << " in no level";
      int lowest = 0;
      for (int b : {g.patches[k].body_a, g.patches[k].body_b}) {
        if (b < 0 || g.bodies[b].inverse_mass == 0) continue;
        lowest = std::max(lowest, last[b] + 1);
        EXPECT_GT(level_of[k], last[b]) << "body " << b << " out of patch order at patch " << k;
      }
      EXPECT_EQ(level_of[k], lowest) << "patch " << k;
      for (int b : {g.patches[k].body_a, g.patches[k].body_b})
        if (b >= 0 && g.bodies[b].inverse_mass > 0) last[b] = level_of[k];
    }
    // Body 5's 37 patches on top of its random ones; body 2 is fixed.
    EXPECT_GE(levels, 37);
    EXPECT_LT(levels, n / 20) << "levels many enough to share, few enough to be worth it";
  }
}

}  // namespace test_patch_colouring
}  // namespace tem
