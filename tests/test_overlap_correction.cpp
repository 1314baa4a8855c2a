// The overlap correction's solve (overlap_correction.hpp): the move pushes overlapping points
// apart and opens no point that was already in contact.
#include <gtest/gtest.h>

#include <vector>

#include "forces/semm.hpp"
#include "forces/semm_rows/semm_rows.hpp"

namespace tem {
namespace test_overlap_correction {

// Body 0 sinks into the floor beyond the slop and is to be lifted at speed 1; body 1 hangs
// below it, in contact (the normal from 0 into 1 points down), so lifting body 0 alone would
// open that contact. Every point at its body's centre: no turning.
struct HangingPair {
  std::vector<ContactPoint> points;
  std::vector<BodyResponse> bodies{2};
  std::vector<Vec3> centres{Vec3::Zero(), Vec3(0, 0, -1)};
  std::vector<PatchFriction> patches{2};
  std::vector<Real> targets{1, 0};

  HangingPair() {
    for (BodyResponse& b : bodies) {
      b.inverse_mass = 1;
      b.angular = Mat3::Identity();
    }
    const Vec3 down = -Vec3::UnitZ();
    // The floor: a wall (B) under body 0 (A); the normal from A into the wall.
    points.push_back({0, 0, -1, 0, centres[0], down, Vec3::UnitX(), -Vec3::UnitY(), 1e-3});
    points.push_back({1, 0, 1, -1, centres[0], down, Vec3::UnitX(), -Vec3::UnitY(), 0});
    for (int k = 0; k < 2; ++k) {
      patches[k].first = k;
      patches[k].last = k + 1;
      patches[k].body_a = 0;
      patches[k].body_b = k == 0 ? -1 : 1;
      patches[k].wall = k == 0 ? 0 : -1;
      patches[k].centre = points[k].point;
      patches[k].normal = down;
    }
  }

  std::vector<BodyResponse> move(const std::vector<char>* held) {
    SolverSettings stopping;
    stopping.tolerance = 1e-12;
    stopping.max_sweeps = 200;
    stopping.held = held;
    std::vector<PatchFriction> working = patches;
    std::vector<PointImpulse> impulses;
    std::vector<BodyResponse> moved;
    RowSolverMemory rows;
    const SolverReport report = solve_separation(points, targets, bodies, centres, working,
                                                 impulses, moved, stopping, &rows);
    EXPECT_TRUE(report.converged);
    return moved;
  }
};

TEST(OverlapCorrection, HeldContactIsCarriedAlongNotOpened) {
  HangingPair pair;
  // Without holding, body 0 rises alone and the contact below it opens by the whole move.
  const auto apart = pair.move(nullptr);
  EXPECT_NEAR(apart[0].velocity.z(), 1, 1e-12);
  EXPECT_NEAR(apart[1].velocity.z(), 0, 1e-12);
  // Held, the contact pulls body 1 along: both rise together, the floor's push lifting both.
  const std::vector<char> held{0, 1};
  const auto together = pair.move(&held);
  EXPECT_NEAR(together[0].velocity.z(), 1, 1e-12);
  EXPECT_NEAR(together[1].velocity.z(), 1, 1e-12);
  EXPECT_NEAR(together[0].velocity.x(), 0, 1e-12);
  EXPECT_NEAR(together[1].velocity.y(), 0, 1e-12);
}

// Holding changes nothing where the move would close a contact: a body resting on top of one
// that is lifted rises with it, held or not.
TEST(OverlapCorrection, BodyOnTopRisesEitherWay) {
  HangingPair pair;
  // Body 1 on top of body 0: the normal from 0 into 1 points up.
  pair.centres[1] = Vec3(0, 0, 1);
  pair.points[1].normal = pair.patches[1].normal = Vec3::UnitZ();
  const std::vector<char> held{0, 1};
  for (const std::vector<char>* h : {static_cast<const std::vector<char>*>(nullptr), &held}) {
    const auto moved = pair.move(h);
    EXPECT_NEAR(moved[0].velocity.z(), 1, 1e-12);
    EXPECT_NEAR(moved[1].velocity.z(), 1, 1e-12);
  }
}

}  // namespace test_overlap_correction
}  // namespace tem
