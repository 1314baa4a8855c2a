// Moving the planes of the approximate cutter's tree (CutTree::refine_planes, cut_tree.hpp).
// The tree grows one greedy cut at a time, each plane chosen for the cuts its look ahead
// foresaw; once the cells below it are cut, a plane a little shifted or turned often lets
// every block below it hug its part better. So each plane in turn is moved by the best of a
// few shifts and turns, every plane below it kept, while that lowers the sum of the hulls'
// volumes below it: a descent, one plane at a time, on the partition as a whole, which the
// growth never revisits. Only the cells that a moved plane touches change: a cell cut anew
// that holds the same part as before keeps its hull, and all below it, as they are.
#include "mesh/cut_tree.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include <Eigen/Geometry>

#include "mesh/hull_polyhedron.hpp"
#include "mesh/part_components.hpp"
#include "support/parallel.hpp"

namespace tem::approximate {
namespace {

// A plane is shifted by these fractions of its part's extent across it, either way...
constexpr std::array<Real, 6> kShifts{1.0 / 4, 1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128};
// ... or turned by these angles (radians) about two axes across it, either sense, through its
// point nearest the part's mean corner.
constexpr std::array<Real, 6> kTurns{0.5, 0.3, 0.16, 0.08, 0.04, 0.02};
// The most moves of one plane in one pass: a plane still moving after them moves on in the
// next pass, after the planes below it have had their turn.
constexpr int kMovesPerPass = 30;
// A plane whose part has more surface polygons than this stays where the growth put it: each
// of its candidates cuts the part and the cells below it that it touches again. On the meshes
// of 75,000 faces of bench_mesh.cpp, moving the planes of the first two levels too took the
// cutter 116 s against 71 s (bumpy torus), 135 s against 82 s (trefoil knot) and 73 s against
// 42 s (potato), for 1.41 %, 1.66 % and 0.38 % over-coverage against 1.42 %, 1.48 %, 0.39 %.
constexpr size_t kLargestPartMoved = 20000;

std::vector<CutPlane> moved_planes(const CutPlane& plane, const std::vector<Vec3>& points) {
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) {
    lo = std::min(lo, plane.normal.dot(p));
    hi = std::max(hi, plane.normal.dot(p));
    mean += p;
  }
  mean /= static_cast<Real>(std::max<size_t>(points.size(), 1));
  std::vector<CutPlane> planes;
  for (Real shift : kShifts)
    for (Real sense : {-1.0, 1.0})
      planes.push_back({plane.normal, plane.offset + sense * shift * (hi - lo)});
  const Vec3 through = mean - (plane.normal.dot(mean) - plane.offset) * plane.normal;
  const Vec3 u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
  for (Real angle : kTurns)
    for (const Vec3& axis : {u, v})
      for (Real sense : {-1.0, 1.0}) {
        const Vec3 turned = Eigen::AngleAxis<Real>(sense * angle, axis) * plane.normal;
        planes.push_back({turned, turned.dot(through)});
      }
  return planes;
}

}  // namespace

bool CutTree::plain_below(int n) const {
  const Node& node = nodes_[n];
  if (!node.alive || node.leaf.merged) return false;
  if (node.children.empty()) return true;
  if (!node.plane) return false;
  return std::all_of(node.children.begin(), node.children.end(),
                     [&](int c) { return plain_below(c); });
}

std::vector<int> CutTree::leaves_below(int n) const {
  std::vector<int> leaves;
  for (std::vector<int> stack{n}; !stack.empty();) {
    const int k = stack.back();
    stack.pop_back();
    if (nodes_[k].children.empty()) leaves.push_back(k);
    stack.insert(stack.end(), nodes_[k].children.begin(), nodes_[k].children.end());
  }
  return leaves;
}

std::optional<std::vector<MeshPart>> CutTree::child_parts(int n, const MeshPart& part,
                                                          const CutPlane& plane,
                                                          bool keep_surface) const {
  const Node& node = nodes_[n];
  const int counts[2] = {node.first_side_pieces,
                         static_cast<int>(node.children.size()) - node.first_side_pieces};
  keep_surface |= counts[0] > 1 || counts[1] > 1;  // pieces are found from the surface
  for (int c : node.children) keep_surface |= !nodes_[c].children.empty();
  auto sides = cut_part(part, plane, keep_surface);
  std::vector<MeshPart> parts;
  const Real gap = kWeld * radius_about_mean(part.points);
  for (int s = 0; s < 2; ++s) {
    if (!(sides[s].volume >= kSmallestSide * part.volume)) return std::nullopt;
    if (counts[s] == 1) {
      parts.push_back(std::move(sides[s]));
      continue;
    }
    auto pieces = separate_groups(sides[s], kSmallestSide * part.volume, gap);
    if (static_cast<int>(pieces.size()) != counts[s]) return std::nullopt;
    for (MeshPart& piece : pieces) parts.push_back(std::move(piece));
  }
  return parts;
}

bool CutTree::holds(int n, const MeshPart& part) const {
  const MeshPart& now = nodes_[n].leaf.part;
  if (part.points != now.points) return false;
  return nodes_[n].children.empty() ||
         (part.volume == now.volume && part.corners == now.corners &&
          part.polygon_start == now.polygon_start && part.caps.size() == now.caps.size());
}

std::optional<Real> CutTree::hulls_below(int n, const MeshPart& part,
                                         const CutPlane& plane) const {
  const auto parts = child_parts(n, part, plane, false);
  if (!parts) return std::nullopt;
  Real sum = 0;
  for (size_t k = 0; k < parts->size(); ++k) {
    const int c = nodes_[n].children[k];
    if (holds(c, (*parts)[k])) {
      for (int leaf : leaves_below(c)) sum += nodes_[leaf].leaf.hull_volume;
    } else if (nodes_[c].children.empty()) {
      sum += hull_volume((*parts)[k].points);
    } else {
      const auto below = hulls_below(c, (*parts)[k], *nodes_[c].plane);
      if (!below) return std::nullopt;
      sum += *below;
    }
  }
  return sum;
}

std::optional<std::vector<std::pair<int, Leaf>>> CutTree::rebuilt_below(
    int n, const MeshPart& part, const CutPlane& plane) const {
  auto parts = child_parts(n, part, plane, true);
  if (!parts) return std::nullopt;
  std::vector<std::pair<int, Leaf>> rebuilt;
  for (size_t k = 0; k < parts->size(); ++k) {
    const int c = nodes_[n].children[k];
    MeshPart& child_part = (*parts)[k];
    if (holds(c, child_part)) continue;
    Leaf leaf;
    leaf.hull_volume = hull_volume(child_part.points);
    if (!nodes_[c].children.empty()) {  // its block and distance wait until asked for
      auto below = rebuilt_below(c, child_part, *nodes_[c].plane);
      if (!below) return std::nullopt;
      leaf.part = std::move(child_part);
      rebuilt.emplace_back(c, std::move(leaf));
      for (auto& entry : *below) rebuilt.push_back(std::move(entry));
      continue;
    }
    auto block = hull_block(child_part.points, kWeld * radius_about_mean(child_part.points));
    if (!block) return std::nullopt;
    leaf.block = std::move(*block);
    // Sampled, to weigh the move by; settle() finds it once the moves are done.
    leaf.distance = sampled_outside_distance(*context_.distance, leaf.block);
    leaf.part = std::move(child_part);
    rebuilt.emplace_back(c, std::move(leaf));
  }
  return rebuilt;
}

void CutTree::settle(int n) {
  Node& node = nodes_[n];
  if (!node.unsettled) return;
  node.unsettled = false;
  if (!node.children.empty()) {  // a leaf's block was made with its part (rebuilt_below)
    auto block =
        hull_block(node.leaf.part.points, kWeld * radius_about_mean(node.leaf.part.points));
    if (!block) {  // cannot be a block again: never merged back
      node.leaf.distance = std::numeric_limits<Real>::infinity();
      return;
    }
    node.leaf.block = std::move(*block);
  }
  node.leaf.distance =
      largest_outside_distance(*context_.distance, {node.leaf.block}, context_.precision);
}

bool CutTree::move_plane(int n) {
  const MeshPart& part = nodes_[n].leaf.part;
  Real hulls = 0, strays = distance_goal_;
  for (int leaf : leaves_below(n)) {
    hulls += nodes_[leaf].leaf.hull_volume;
    strays = std::max(strays, nodes_[leaf].leaf.distance);
  }
  const std::vector<CutPlane> planes = moved_planes(*nodes_[n].plane, part.points);
  std::vector<Real> sums(planes.size(), std::numeric_limits<Real>::infinity());
  parallel_for(
      static_cast<long long>(planes.size()), 1,
      [&](long long c) {
        if (auto sum = hulls_below(n, part, planes[c])) sums[c] = *sum;
      },
      true);
  std::vector<int> order;
  for (size_t c = 0; c < planes.size(); ++c)
    if (sums[c] < hulls - smallest_gain_) order.push_back(static_cast<int>(c));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sums[a] < sums[b]; });
  // A merged block reaches outside its cells, so a moved cell's block may not reach into one
  // (blocks never overlap).
  std::vector<const Leaf*> merged;
  for (const Node& other : nodes_)
    if (other.is_leaf() && other.leaf.merged) merged.push_back(&other.leaf);
  for (int c : order) {
    auto rebuilt = rebuilt_below(n, part, planes[c]);
    if (!rebuilt) continue;
    const bool fits = std::all_of(rebuilt->begin(), rebuilt->end(), [&](const auto& entry) {
      const auto& [k, leaf] = entry;
      return !nodes_[k].children.empty() ||
             (!(leaf.distance > strays) && !reaches_into(leaf.block, merged, touching_));
    });
    if (!fits) continue;
    for (auto& [k, leaf] : *rebuilt) {
      Node& node = nodes_[k];
      node.leaf = std::move(leaf);
      node.unsettled = node.moved_below = true;
      node.next.reset();
      node.next_known = false;
    }
    nodes_[n].plane = planes[c];
    touched(n);
    return true;
  }
  return false;
}

bool CutTree::refine_planes() {
  bool moved = false;
  for (size_t n = 0; n < nodes_.size(); ++n) {  // a node's parent comes before it
    // A plane that found no move finds none again until something below it changes.
    if (nodes_[n].children.empty() || !nodes_[n].moved_below ||
        nodes_[n].leaf.part.polygon_start.size() > kLargestPartMoved + 1 ||
        !plain_below(static_cast<int>(n)))
      continue;
    int move = 0;
    while (move < kMovesPerPass && move_plane(static_cast<int>(n))) ++move;
    if (move < kMovesPerPass) nodes_[n].moved_below = false;
    moved |= move > 0;
  }
  for (size_t n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].children.empty()) settle(static_cast<int>(n));
  if (moved) {  // the pairs' costs and verdicts were the old leaves'
    leaf_pairs_.clear();
    paired_ = 0;
  }
  return moved;
}

}  // namespace tem::approximate
