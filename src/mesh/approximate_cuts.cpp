// Cutting one part for the approximate cutter (approximate_cuts.hpp).
#include "mesh/approximate_cuts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "geometry/aabb.hpp"
#include "mass/surface_integrals.hpp"
#include "mesh/approximate_lookahead.hpp"
#include "mesh/convex_overlap.hpp"
#include "mesh/hull_polyhedron.hpp"
#include "mesh/part_components.hpp"
#include "support/parallel.hpp"

namespace tem::approximate {
namespace {

// Evenly spaced candidate offsets per direction; the best is then refined twice, by half and
// a quarter of their spacing.
constexpr int kOffsets = 8;
// Along a direction where the part's corners take at most this many positions strictly inside
// its extent, the planes through them are the candidates (they cut boxes exactly).
constexpr int kExactOffsets = 16;
// Tilts of the best plane's normal, in radians, each about the best plane after the last.
constexpr std::array<Real, 3> kTilts{0.16, 0.08, 0.04};
// Candidate planes are ranked by distance on the hull of the sides' corners thinned to one per
// cell of a grid this many cells long (a 75,000-face part has tens of thousands of corners).
constexpr int kDistanceCloudCells = 32;

struct Candidate {
  CutPlane plane;
  Real spacing = 0;  // between neighbouring evenly spaced offsets; 0 for a plane through corners
  Real score = std::numeric_limits<Real>::infinity();  // inf: refused (a side too small)
  Real worst = 0;                                      // the larger side concavity
  std::array<Real, 2> hull_volume{0, 0};
  Real distance = 0;  // the larger side's distance outside the mesh, when cutting for distance
  bool tried = false;
};

// About how far the hull of these points strays outside the mesh (sampled, to rank candidate
// cuts); infinite if they span no hull. The hull is Qhull's, unchecked: whether a side makes a
// block is settled once a cut is chosen (leaves_of), and checking every candidate's hull as a
// block cost as much as sampling it.
Real block_distance(const std::vector<Vec3>& points, const Context& context) {
  auto hull = hull_polyhedron(thinned_cloud(points, kDistanceCloudCells));
  if (!hull) return std::numeric_limits<Real>::infinity();
  return sampled_outside_distance(*context.distance, *hull);
}

// x, y, z, the six face and four body diagonals of a cube (an ear or a blade at an angle is cut
// off closer to its root), then the principal axes of the part's volume not already among them.
std::vector<Vec3> cut_directions(const MeshPart& part) {
  std::vector<Vec3> directions{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  for (const Vec3& d : {Vec3(1, 1, 0), Vec3(1, -1, 0), Vec3(1, 0, 1), Vec3(1, 0, -1),
                        Vec3(0, 1, 1), Vec3(0, 1, -1), Vec3(1, 1, 1), Vec3(1, 1, -1),
                        Vec3(1, -1, 1), Vec3(-1, 1, 1)})
    directions.push_back(d.normalized());
  const MassProperties mass = surface_mass_properties(part_triangles(part));
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(mass.second_moment);
  for (int k = 2; k >= 0; --k) {  // the longest axis first
    const Vec3 axis = eigen.eigenvectors().col(k).normalized();
    if (axis.allFinite() && axis.cwiseAbs().maxCoeff() < 0.999) directions.push_back(axis);
  }
  return directions;
}

void add_candidates(const MeshPart& part, const Vec3& direction, std::vector<Candidate>& out) {
  std::vector<Real> along;
  along.reserve(part.points.size());
  for (const Vec3& p : part.points) along.push_back(direction.dot(p));
  std::sort(along.begin(), along.end());
  if (along.empty() || !(along.back() > along.front())) return;
  const Real lo = along.front(), hi = along.back(), same = 1e-9 * (hi - lo);
  std::vector<Real> inner;
  for (Real a : along)
    if (a > lo + same && a < hi - same && (inner.empty() || a > inner.back() + same)) {
      inner.push_back(a);
      if (static_cast<int>(inner.size()) > kExactOffsets) break;
    }
  if (static_cast<int>(inner.size()) <= kExactOffsets) {
    for (Real a : inner) out.push_back({{direction, a}, 0});
    return;
  }
  const Real spacing = (hi - lo) / (kOffsets + 1);
  for (int i = 1; i <= kOffsets; ++i) out.push_back({{direction, lo + i * spacing}, spacing});
}

void score(const MeshPart& part, Candidate& candidate, const Context& context) {
  const auto sides = cut_part(part, candidate.plane, false);
  for (const MeshPart& side : sides)
    if (!(side.volume >= kSmallestSide * part.volume)) return;
  for (int s = 0; s < 2; ++s) candidate.hull_volume[s] = hull_volume(sides[s].points);
  candidate.score = candidate.hull_volume[0] + candidate.hull_volume[1];
  if (context.lookahead > 0)
    candidate.score -= context.lookahead * (lookahead_gain(sides[0].points) +
                                            lookahead_gain(sides[1].points));
  candidate.worst = std::max(candidate.hull_volume[0] - sides[0].volume,
                             candidate.hull_volume[1] - sides[1].volume);
  if (context.for_distance)
    candidate.distance = std::max(block_distance(sides[0].points, context),
                                  block_distance(sides[1].points, context));
}

void score_all(const MeshPart& part, std::vector<Candidate>& candidates, size_t first,
               const Context& context) {
  parallel_for(
      static_cast<long long>(candidates.size() - first), 1,
      [&](long long i) { score(part, candidates[first + i], context); }, true);
}

// Whether a ranks before b: by distance when cutting for it (within the distances' precision),
// then by score; scores within `tie` of each other are equal.
bool better(const Candidate& a, const Candidate& b, const Context& context) {
  if (context.for_distance) {
    if (a.distance < b.distance - context.precision) return true;
    if (a.distance > b.distance + context.precision) return false;
  }
  const Real tie = context.tie;
  if (a.score < b.score - tie) return true;
  if (a.score > b.score + tie) return false;
  return a.worst < b.worst - tie;
}

// The best candidate not tried yet (the first of equals), or -1.
int best_untried(const std::vector<Candidate>& candidates, const Context& context) {
  int best = -1;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    if (c.tried || !std::isfinite(c.score)) continue;
    if (best < 0 || better(c, candidates[best], context)) best = static_cast<int>(i);
  }
  return best;
}

// Tilts the best candidate's normal by each of kTilts in turn, four ways (about two axes across
// it, either sense), about the plane's point nearest the mean of the part's corners, so that the
// part is cut at about the same place.
void tilt_best(const MeshPart& part, std::vector<Candidate>& candidates, const Context& context) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : part.points) mean += p;
  mean /= static_cast<Real>(std::max<size_t>(part.points.size(), 1));
  for (Real angle : kTilts) {
    const int best = best_untried(candidates, context);
    if (best < 0) return;
    const CutPlane plane = candidates[best].plane;
    const Vec3 through = mean - (plane.normal.dot(mean) - plane.offset) * plane.normal;
    const Vec3 u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
    const size_t first = candidates.size();
    for (const Vec3& axis : {u, v})
      for (Real sense : {-1.0, 1.0}) {
        const Vec3 tilted = Eigen::AngleAxis<Real>(sense * angle, axis) * plane.normal;
        candidates.push_back({{tilted, tilted.dot(through)}, 0});
      }
    score_all(part, candidates, first, context);
  }
}

}  // namespace

Split split_into(Real hull, std::vector<Leaf> children) {
  Split split{std::move(children), hull, std::nullopt, 0};
  for (const Leaf& child : split.children) split.gain -= child.hull_volume;
  return split;
}

std::optional<std::vector<Leaf>> leaves_of(std::vector<MeshPart> parts, const Context& context) {
  std::vector<Leaf> leaves;
  for (MeshPart& part : parts) {
    auto block = hull_block(part.points, kWeld * radius_about_mean(part.points));
    if (!block) return std::nullopt;
    const Real volume = hull_volume(part.points);
    leaves.push_back({std::move(part), std::move(*block), volume});
  }
  for (Leaf& leaf : leaves)
    leaf.distance = largest_outside_distance(*context.distance, {leaf.block}, context.precision);
  return leaves;
}

std::optional<Split> split(const Leaf& leaf, Context context) {
  std::vector<Candidate> candidates;
  for (const Vec3& direction : cut_directions(leaf.part))
    add_candidates(leaf.part, direction, candidates);
  score_all(leaf.part, candidates, 0, context);
  // Cutting for distance only pays where some plane brings it down (estimate against
  // estimate); a hole's rim, for one, needs several cuts before any does: cut by volume then.
  if (context.for_distance) {
    const int best = best_untried(candidates, context);
    if (best < 0 || !(candidates[best].distance <
                      sampled_outside_distance(*context.distance, leaf.block) - context.precision))
      context.for_distance = false;
  }
  // Refine an evenly spaced best: half, then a quarter of the spacing to either side.
  for (int round = 0; round < 2; ++round) {
    const int best = best_untried(candidates, context);
    if (best < 0 || candidates[best].spacing == 0) break;
    const Candidate centre = candidates[best];
    const Real step = centre.spacing / 2;
    const size_t first = candidates.size();
    for (Real offset : {centre.plane.offset - step, centre.plane.offset + step})
      candidates.push_back({{centre.plane.normal, offset}, step});
    score_all(leaf.part, candidates, first, context);
  }
  tilt_best(leaf.part, candidates, context);
  const Real gap = kWeld * radius_about_mean(leaf.part.points);
  for (int best; (best = best_untried(candidates, context)) >= 0;) {
    Candidate& chosen = candidates[best];
    chosen.tried = true;
    auto sides = cut_part(leaf.part, chosen.plane, true);
    std::vector<MeshPart> pieces;
    int first_side_pieces = 0;
    for (int s = 0; s < 2; ++s)
      for (MeshPart& group : separate_groups(sides[s], kSmallestSide * leaf.part.volume, gap)) {
        pieces.push_back(std::move(group));
        if (s == 0) ++first_side_pieces;
      }
    auto children = pieces.size() <= static_cast<size_t>(context.room)
                        ? leaves_of(std::move(pieces), context)
                        : std::nullopt;
    if (!children) {
      children = leaves_of({std::move(sides[0]), std::move(sides[1])}, context);
      first_side_pieces = 1;
    }
    if (!children) continue;
    Split result = split_into(leaf.hull_volume, std::move(*children));
    result.plane = chosen.plane;
    result.first_side_pieces = first_side_pieces;
    return result;
  }
  return std::nullopt;
}

Real merge_cost(const Leaf& a, const Leaf& b) {
  std::vector<Vec3> both = a.block.points;
  both.insert(both.end(), b.block.points.begin(), b.block.points.end());
  return hull_volume(both) - a.hull_volume - b.hull_volume;
}

bool reaches_into(const PolyhedronDef& block, const std::vector<const Leaf*>& others, Real eps) {
  const Aabb box = Aabb::around(block.points);
  return std::any_of(others.begin(), others.end(), [&](const Leaf* other) {
    return box.within(Aabb::around(other->block.points), eps) &&
           !convex_insides_apart(block, other->block, eps);
  });
}

std::optional<Leaf> merged_leaf(const Leaf& a, const Leaf& b,
                                const std::vector<const Leaf*>& others, Real distance_goal,
                                Real eps, const Context& context) {
  MeshPart part;
  part.points = a.part.points;
  part.points.insert(part.points.end(), b.part.points.begin(), b.part.points.end());
  part.volume = a.part.volume + b.part.volume;
  auto block = hull_block(part.points, kWeld * radius_about_mean(part.points));
  if (!block || reaches_into(*block, others, eps)) return std::nullopt;
  const Real distance = largest_outside_distance(*context.distance, {*block}, context.precision);
  if (distance > std::max({distance_goal, a.distance, b.distance})) return std::nullopt;
  Leaf leaf;
  leaf.hull_volume = hull_volume(part.points);
  leaf.part = std::move(part);
  leaf.block = std::move(*block);
  leaf.distance = distance;
  leaf.final = leaf.merged = true;
  return leaf;
}

}  // namespace tem::approximate
