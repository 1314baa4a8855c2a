#include "contact/patches.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

namespace tem {
namespace {

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// The smaller index stays the root, so groups do not depend on the order of unions.
void unite(std::vector<int>& parent, int x, int y) {
  x = find(parent, x);
  y = find(parent, y);
  if (x < y)
    parent[y] = x;
  else if (y < x)
    parent[x] = y;
}

// Steps 1-3 of the grouping inside one block whose node slots start at `offset`.
void join_within_block(const Block& block, const std::vector<NodeHit>& nodes,
                       const std::vector<EdgeHit>& edges, int offset, PatchScratch& s) {
  s.flagged_node.assign(block.nodes().size(), 0);
  s.flagged_edge.assign(block.edges().size(), 0);
  for (const NodeHit& h : nodes) s.flagged_node[h.node] = 1;
  for (const EdgeHit& h : edges) s.flagged_edge[h.edge] = 1;
  for (size_t k = 0; k < block.edges().size(); ++k) {
    const auto [u, w] = block.edges()[k].nodes;
    if (s.flagged_node[u] || s.flagged_node[w] || s.flagged_edge[k]) {
      unite(s.parent, offset + u, offset + w);
      s.active[offset + u] = s.active[offset + w] = 1;
    }
  }
}

// Step 4: an edge of one side through a triangle of the other joins the other side's group that
// touches that triangle.
void join_across(const Block& own, const std::vector<EdgeHit>& edges, int own_offset,
                 const Block& other, int other_offset, PatchScratch& s) {
  for (const EdgeHit& h : edges) {
    const int mine = own_offset + own.edges()[h.edge].nodes[0];
    for (int v : other.triangles()[h.triangle].nodes)
      if (s.active[other_offset + v]) unite(s.parent, mine, other_offset + v);
  }
}

// Running sums of one side of one group.
struct SideSums {
  Vec3 nodes = Vec3::Zero(), node_normals = Vec3::Zero();
  int node_count = 0;
  Vec3 edges = Vec3::Zero(), edge_normals = Vec3::Zero();
  int edge_count = 0;
  // The other side's edges through this side's faces: points on this side's surface.
  Vec3 crossings = Vec3::Zero(), crossed_normals = Vec3::Zero();
  int crossing_count = 0;

  bool empty() const { return node_count + edge_count + crossing_count == 0; }
  // The paper's point and normal of one side (§4.4).
  std::pair<Vec3, Vec3> point_and_normal() const {
    if (node_count > 0) return {nodes / node_count, node_normals.normalized()};
    if (edge_count > 0) return {edges / edge_count, edge_normals.normalized()};
    return {crossings / crossing_count, crossed_normals.normalized()};
  }
};

struct Group {
  SideSums a, b;
  Vec3 normal_sum = Vec3::Zero();  // default variant, from A into B
  std::vector<Vec3> face_normals;  // of the faces the features went through, from A into B
  std::vector<Vec3> edges_a, edges_b;  // world directions of the polygon edges that cross
  std::vector<Vec3> vertices;
  int features = 0;
};

void add_bounds(ContactPatch& p) {
  if (p.vertices.empty()) {
    p.bounds_min = p.bounds_max = p.point;
    return;
  }
  p.bounds_min = p.bounds_max = p.vertices[0];
  for (const Vec3& v : p.vertices) {
    p.bounds_min = p.bounds_min.cwiseMin(v);
    p.bounds_max = p.bounds_max.cwiseMax(v);
  }
}

// Extent of the vertices along n: the overlap's depth in the default variant.
Real extent_along(const std::vector<Vec3>& vertices, const Vec3& n) {
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
  for (const Vec3& v : vertices) {
    lo = std::min(lo, n.dot(v));
    hi = std::max(hi, n.dot(v));
  }
  return vertices.empty() ? 0 : hi - lo;
}

// Range of a block's nodes projected on a world direction.
std::pair<Real, Real> projection(const Block& block, const BlockPose& pose, const Vec3& n) {
  const Vec3 local = pose.rotation.transpose() * n;  // n . (R x + p) = (R^T n) . x + n . p
  const Real shift = n.dot(pose.position);
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
  for (const Vec3& x : block.nodes()) {
    lo = std::min(lo, local.dot(x));
    hi = std::max(hi, local.dot(x));
  }
  return {lo + shift, hi + shift};
}

// Turns an axis so that it points from A into B, as the separating-axis theorem does: A lies on
// the low side when pushing it back along the axis takes less than pushing it forward. The
// faces the features crossed cannot be trusted for this: an edge of B leaving A through a
// sloping face of A has that face's outward normal, which can point anywhere but into B.
Vec3 oriented(const Vec3& axis, const Vec3& sum, const Block& a, const BlockPose& pose_a,
              const Block& b, const BlockPose& pose_b) {
  const auto [a_lo, a_hi] = projection(a, pose_a, axis);
  const auto [b_lo, b_hi] = projection(b, pose_b, axis);
  const Real forward = a_hi - b_lo, backward = b_hi - a_lo;
  if (forward != backward) return forward < backward ? axis : Vec3(-axis);
  return axis.dot(sum) >= 0 ? axis : Vec3(-axis);
}

// The default normal: among the normals of the faces the features went through, their sum, and
// the cross products of crossing edges of A and B (the normal of an edge-edge contact), the
// axis along which the overlap region is thinnest, i.e. the shortest way out (as the
// separating-axis theorem picks it), turned to point from A into B. Axes within round-off of
// the thinnest are decided by the largest component along the sum, so that swapping A and B
// only flips the result.
std::pair<Vec3, Real> thinnest_normal(const Group& g, const Block& a, const BlockPose& pose_a,
                                      const Block& b, const BlockPose& pose_b) {
  const Vec3 sum = g.normal_sum.normalized();
  std::vector<Vec3> axes = g.face_normals;
  axes.push_back(sum);
  for (const Vec3& ea : g.edges_a)
    for (const Vec3& eb : g.edges_b) {
      const Vec3 c = ea.cross(eb);
      if (c.norm() > 1e-9 * ea.norm() * eb.norm()) axes.push_back(c.normalized());
    }
  std::vector<Real> extent(axes.size());
  Real best = std::numeric_limits<Real>::infinity();
  for (size_t i = 0; i < axes.size(); ++i) {
    extent[i] = extent_along(g.vertices, axes[i]);
    best = std::min(best, extent[i]);
  }
  const Real within = best + 1e-12 * (1 + best);
  Vec3 chosen = sum;
  Real chosen_extent = extent_along(g.vertices, sum);
  Real along_sum = -std::numeric_limits<Real>::infinity();
  for (size_t i = 0; i < axes.size(); ++i) {
    if (extent[i] > within) continue;
    const Vec3 n = oriented(axes[i], sum, a, pose_a, b, pose_b);
    if (n.dot(sum) > along_sum) {
      along_sum = n.dot(sum);
      chosen = n;
      chosen_extent = extent[i];
    }
  }
  return {chosen, chosen_extent};
}

Vec3 mean(const std::vector<Vec3>& points) {
  Vec3 m = Vec3::Zero();
  for (const Vec3& p : points) m += p;
  return m / static_cast<Real>(std::max<size_t>(points.size(), 1));
}

// Index of the group that the slot's root stands for, made on first sight.
int group_index(PatchScratch& s, std::vector<Group>& groups, int slot) {
  const int root = find(s.parent, slot);
  if (s.group_of_root[root] < 0) {
    s.group_of_root[root] = static_cast<int>(groups.size());
    groups.emplace_back();
  }
  return s.group_of_root[root];
}

// Adds one side's hits to their groups. `sign` turns the crossed faces' outward normals into
// the direction from A into B: -1 for A's hits (B's faces point from B to A), +1 for B's.
void accumulate(const Block& own, const BlockPose& pose, const std::vector<NodeHit>& nodes,
                const std::vector<EdgeHit>& edges, int offset, Real sign, bool side_a,
                PatchScratch& s, std::vector<Group>& groups) {
  for (const NodeHit& h : nodes) {
    Group& g = groups[group_index(s, groups, offset + h.node)];
    SideSums& mine = side_a ? g.a : g.b;
    mine.nodes += h.point;
    mine.node_normals += pose.rotation * own.node_normal(h.node, NormalVariant::paper);
    ++mine.node_count;
    g.normal_sum += sign * h.face_normal;
    g.face_normals.push_back(sign * h.face_normal);
    g.vertices.push_back(h.point);
    ++g.features;
  }
  for (const EdgeHit& h : edges) {
    const Edge& e = own.edges()[h.edge];
    Group& g = groups[group_index(s, groups, offset + e.nodes[0])];
    SideSums& mine = side_a ? g.a : g.b;
    SideSums& theirs = side_a ? g.b : g.a;
    mine.edges += h.point;
    mine.edge_normals += pose.rotation * own.edge_normal(h.edge, NormalVariant::paper);
    ++mine.edge_count;
    theirs.crossings += h.point;
    theirs.crossed_normals += h.face_normal;
    ++theirs.crossing_count;
    ++g.features;
    if (e.polygon_boundary) {  // diagonals of planar polygons are not corners of the overlap
      g.normal_sum += sign * h.face_normal;
      g.face_normals.push_back(sign * h.face_normal);
      (side_a ? g.edges_a : g.edges_b)
          .push_back(pose.rotation * (own.nodes()[e.nodes[1]] - own.nodes()[e.nodes[0]]));
      g.vertices.push_back(h.point);
    }
  }
}

void prepare(PatchScratch& s, size_t slots) {
  s.parent.resize(slots);
  for (size_t i = 0; i < slots; ++i) s.parent[i] = static_cast<int>(i);
  s.active.assign(slots, 0);
  s.group_of_root.assign(slots, -1);
}

}  // namespace

void pair_patches(const Block& a, const BlockPose& pose_a, const Block& b,
                  const BlockPose& pose_b, const PairFeatures& f, PatchVariant variant,
                  PatchScratch& s, std::vector<ContactPatch>& out) {
  if (f.empty()) return;
  const int nb = static_cast<int>(a.nodes().size());  // B's node slots start here
  prepare(s, a.nodes().size() + b.nodes().size());
  join_within_block(a, f.a.nodes, f.a.edges, 0, s);
  join_within_block(b, f.b.nodes, f.b.edges, nb, s);
  join_across(a, f.a.edges, 0, b, nb, s);
  join_across(b, f.b.edges, nb, a, 0, s);

  std::vector<Group> groups;
  accumulate(a, pose_a, f.a.nodes, f.a.edges, 0, -1, true, s, groups);
  accumulate(b, pose_b, f.b.nodes, f.b.edges, nb, +1, false, s, groups);

  for (Group& g : groups) {
    ContactPatch p;
    p.features = g.features;
    // Paper variant, also the fallback where the default normal cancels out.
    auto [pa, na] = g.a.point_and_normal();
    auto [pb, nb_] = g.b.point_and_normal();
    if (g.a.empty()) std::tie(pa, na) = std::make_pair(pb, Vec3(-nb_));
    if (g.b.empty()) std::tie(pb, nb_) = std::make_pair(pa, Vec3(-na));
    const Vec3 paper_normal = (na - nb_).normalized();
    if (variant == NormalVariant::paper || g.normal_sum.norm() < 1e-12 * g.features) {
      p.normal = paper_normal;
      p.point = (pa + pb) / 2;
      p.depth = (pa - pb).dot(p.normal);
    } else {
      std::tie(p.normal, p.depth) = thinnest_normal(g, a, pose_a, b, pose_b);
      p.point = mean(g.vertices);
    }
    p.vertices = std::move(g.vertices);
    add_bounds(p);
    out.push_back(std::move(p));
  }
}

void wall_patches(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                  const Vec3& wall_normal, const WallFeatures& f, PatchVariant variant,
                  PatchScratch& s, std::vector<ContactPatch>& out) {
  if (f.empty()) return;
  prepare(s, block.nodes().size());
  join_within_block(block, f.nodes, f.edges, 0, s);
  std::vector<Group> groups;
  // Every node behind the plane and every edge through it, with the wall's exact normal.
  accumulate(block, pose, f.nodes, f.edges, 0, -1, true, s, groups);
  for (Group& g : groups) {
    if (g.a.node_count == 0) continue;  // edges alone cannot be behind a plane
    ContactPatch p;
    p.features = g.features;
    if (variant == NormalVariant::paper) {
      // The body's side by the node-normal rule; the wall's normal is the other side's.
      const auto [pa, na] = g.a.point_and_normal();
      const Vec3 pb = pa - wall_normal.dot(pa - wall_point) * wall_normal;
      p.normal = (na - wall_normal).normalized();
      p.point = (pa + pb) / 2;
      p.depth = (pa - pb).dot(p.normal);
    } else {
      p.normal = -wall_normal;
      p.point = mean(g.vertices);
      p.depth = extent_along(g.vertices, p.normal);
    }
    p.vertices = std::move(g.vertices);
    add_bounds(p);
    out.push_back(std::move(p));
  }
}

namespace {

bool same_pair(const ContactPatch& p, const ContactPatch& q) {
  return p.body_a == q.body_a && p.body_b == q.body_b && p.wall == q.wall;
}

bool bounds_touch(const ContactPatch& p, const ContactPatch& q) {
  const Real tol =
      1e-9 * ((p.bounds_max - p.bounds_min).norm() + (q.bounds_max - q.bounds_min).norm());
  return (p.bounds_min.array() <= q.bounds_max.array() + tol).all() &&
         (q.bounds_min.array() <= p.bounds_max.array() + tol).all();
}

// Merges the patches [first, last) of one pair whose bounds touch, appending to `merged`. The
// merged point is the mean of all their overlap corners, the normal the mean of their normals
// weighted by their corner counts, the depth the deepest. Corners, not feature counts, are the
// weights: the diagonals of triangulated polygons are features too, and their direction would
// make the result depend on how each polygon happened to be triangulated.
void merge_run(std::vector<ContactPatch>& patches, int first, int last,
               std::vector<ContactPatch>& merged) {
  const int n = last - first;
  std::vector<int> parent(n);
  for (int i = 0; i < n; ++i) parent[i] = i;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (bounds_touch(patches[first + i], patches[first + j])) unite(parent, i, j);
  std::vector<int> index_of_root(n, -1);
  const size_t start = merged.size();
  std::vector<Vec3> normal_sum;
  std::vector<int> parts;
  auto weight = [](const ContactPatch& p) {
    return static_cast<Real>(std::max<size_t>(p.vertices.size(), 1));
  };
  for (int i = 0; i < n; ++i) {
    ContactPatch& p = patches[first + i];
    const int root = find(parent, i);
    if (index_of_root[root] < 0) {
      index_of_root[root] = static_cast<int>(normal_sum.size());
      normal_sum.push_back(weight(p) * p.normal);
      parts.push_back(1);
      merged.push_back(std::move(p));
      continue;
    }
    const int m = index_of_root[root];
    ++parts[m];
    ContactPatch& q = merged[start + m];
    normal_sum[m] += weight(p) * p.normal;
    q.features += p.features;
    q.depth = std::max(q.depth, p.depth);
    q.vertices.insert(q.vertices.end(), p.vertices.begin(), p.vertices.end());
    q.bounds_min = q.bounds_min.cwiseMin(p.bounds_min);
    q.bounds_max = q.bounds_max.cwiseMax(p.bounds_max);
  }
  for (size_t m = 0; m < normal_sum.size(); ++m) {
    if (parts[m] == 1) continue;
    ContactPatch& q = merged[start + m];
    q.normal = normal_sum[m].normalized();
    if (!q.vertices.empty()) q.point = mean(q.vertices);
  }
}

}  // namespace

void merge_touching_patches(std::vector<ContactPatch>& patches) {
  std::vector<ContactPatch> merged;
  merged.reserve(patches.size());
  const int n = static_cast<int>(patches.size());
  for (int first = 0; first < n;) {
    int last = first + 1;
    while (last < n && same_pair(patches[first], patches[last])) ++last;
    merge_run(patches, first, last, merged);
    first = last;
  }
  patches = std::move(merged);
}

}  // namespace tem
