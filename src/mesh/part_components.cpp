// The pieces of a cut part (part_components.hpp). Two polygons that share an edge, and a cap's
// segment on it, carry the same bits at its ends (plane_cut.cpp's crossing), so pieces are the
// classes of corners joined by polygons and cap segments. A cap's hole is the one exception: a
// slab cut from a tube has its outer and inner walls joined only through the caps' solid area,
// so a cap's loop that turns clockwise (a hole) joins the loop around it.
#include "mesh/part_components.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace tem {
namespace {

struct PointKey {
  std::uint64_t bits[3];
  bool operator==(const PointKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct PointKeyHash {
  size_t operator()(const PointKey& k) const {
    std::uint64_t h = k.bits[0] * 0x9E3779B97F4A7C15ull;
    h ^= k.bits[1] + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2);
    h ^= k.bits[2] + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h);
  }
};

PointKey key_of(const Vec3& p) {
  PointKey key;
  for (int i = 0; i < 3; ++i) {
    const Real x = p[i] + 0.0;  // -0 and +0 are one point
    std::memcpy(&key.bits[i], &x, sizeof x);
  }
  return key;
}

class Classes {
 public:
  int id(const Vec3& p) {
    const auto [it, added] = ids_.try_emplace(key_of(p), static_cast<int>(parent_.size()));
    if (added) parent_.push_back(it->second);
    return it->second;
  }
  int find_id(const Vec3& p) const {
    const auto it = ids_.find(key_of(p));
    return it == ids_.end() ? -1 : it->second;
  }
  int root(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(int a, int b) {
    a = root(a);
    b = root(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::unordered_map<PointKey, int, PointKeyHash> ids_;
  std::vector<int> parent_;
};

// Winding number of the cap segments about q, in the cap's plane (u, v about its normal).
int winding(const std::vector<const std::array<Vec3, 2>*>& segments, const Vec3& q,
            const Vec3& u, const Vec3& v) {
  const Real qu = u.dot(q), qv = v.dot(q);
  int w = 0;
  for (const auto* s : segments) {
    const Real au = u.dot((*s)[0]) - qu, av = v.dot((*s)[0]) - qv;
    const Real bu = u.dot((*s)[1]) - qu, bv = v.dot((*s)[1]) - qv;
    if ((av <= 0) == (bv <= 0)) continue;
    const Real cross = au * bv - av * bu;  // > 0: q is left of a -> b
    if (bv > av && cross > 0) ++w;
    else if (bv < av && cross < 0) --w;
  }
  return w;
}

// A cap's loops that turn clockwise (holes) join the class of the smallest loop around them
// that turns counter-clockwise.
void join_holes(const MeshPart::Cap& cap, Classes& classes) {
  struct Loop {
    std::vector<const std::array<Vec3, 2>*> segments;
    Real area = 0;
  };
  std::unordered_map<int, Loop> loops;
  const Vec3 u = cap.plane.normal.unitOrthogonal(), v = cap.plane.normal.cross(u);
  const Vec3 origin = cap.edges.front()[0];
  for (const auto& s : cap.edges) {
    Loop& loop = loops[classes.root(classes.id(s[0]))];
    loop.segments.push_back(&s);
    const Vec3 a = s[0] - origin, b = s[1] - origin;
    loop.area += 0.5 * (u.dot(a) * v.dot(b) - v.dot(a) * u.dot(b));
  }
  if (loops.size() < 2) return;
  std::vector<int> order;  // fixed order: the classes' roots
  for (const auto& [root, loop] : loops) order.push_back(root);
  std::sort(order.begin(), order.end());
  for (int hole : order) {
    const Loop& h = loops[hole];
    if (!(h.area < 0)) continue;
    int around = -1;
    for (int outer : order) {
      const Loop& o = loops[outer];
      if (!(o.area > 0) || winding(o.segments, (*h.segments.front())[0], u, v) == 0) continue;
      if (around < 0 || o.area < loops[around].area) around = outer;
    }
    if (around >= 0) classes.join(hole, around);
  }
}

void append(MeshPart& to, const MeshPart& from) {
  const int shift = static_cast<int>(to.corners.size());
  to.corners.insert(to.corners.end(), from.corners.begin(), from.corners.end());
  if (to.polygon_start.empty()) to.polygon_start.push_back(0);
  for (size_t i = 1; i < from.polygon_start.size(); ++i)
    to.polygon_start.push_back(from.polygon_start[i] + shift);
  to.caps.insert(to.caps.end(), from.caps.begin(), from.caps.end());
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  to.volume += from.volume;
}

Vec3 mean_of(const std::vector<Vec3>& points) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  return mean / static_cast<Real>(std::max<size_t>(points.size(), 1));
}

}  // namespace

std::vector<MeshPart> connected_components(const MeshPart& part) {
  Classes classes;
  const size_t polygons = part.polygon_start.empty() ? 0 : part.polygon_start.size() - 1;
  for (size_t i = 0; i < polygons; ++i) {
    const int first = classes.id(part.corners[part.polygon_start[i]]);
    for (int k = part.polygon_start[i] + 1; k < part.polygon_start[i + 1]; ++k)
      classes.join(first, classes.id(part.corners[k]));
  }
  for (const auto& cap : part.caps)
    for (const auto& s : cap.edges) classes.join(classes.id(s[0]), classes.id(s[1]));
  for (const auto& cap : part.caps)
    if (!cap.edges.empty()) join_holes(cap, classes);

  // Pieces numbered by their smallest corner class: the same order every run.
  std::unordered_map<int, int> piece_of_root;
  std::vector<int> roots;
  auto piece = [&](const Vec3& p) {
    const int id = classes.find_id(p);
    if (id < 0) return -1;
    const int root = classes.root(id);
    const auto [it, added] = piece_of_root.try_emplace(root, static_cast<int>(roots.size()));
    if (added) roots.push_back(root);
    return it->second;
  };
  std::vector<int> polygon_piece(polygons);
  for (size_t i = 0; i < polygons; ++i)
    polygon_piece[i] = piece(part.corners[part.polygon_start[i]]);
  std::vector<int> point_piece(part.points.size());
  for (size_t i = 0; i < part.points.size(); ++i) point_piece[i] = piece(part.points[i]);
  if (roots.size() < 2 || std::count(point_piece.begin(), point_piece.end(), -1) > 0)
    return {part};

  std::vector<MeshPart> pieces(roots.size());
  for (MeshPart& p : pieces) p.polygon_start.push_back(0);
  for (size_t i = 0; i < polygons; ++i) {
    MeshPart& p = pieces[polygon_piece[i]];
    p.corners.insert(p.corners.end(), part.corners.begin() + part.polygon_start[i],
                     part.corners.begin() + part.polygon_start[i + 1]);
    p.polygon_start.push_back(static_cast<int>(p.corners.size()));
  }
  for (const auto& cap : part.caps) {
    std::vector<int> used;  // pieces given a share of this cap, in order
    for (const auto& s : cap.edges) {
      const int k = piece(s[0]);
      if (k < 0) return {part};
      if (std::find(used.begin(), used.end(), k) == used.end()) {
        used.push_back(k);
        pieces[k].caps.push_back({cap.plane, {}});
      }
      pieces[k].caps.back().edges.push_back(s);
    }
  }
  for (size_t i = 0; i < part.points.size(); ++i)
    pieces[point_piece[i]].points.push_back(part.points[i]);
  for (MeshPart& p : pieces) {
    p.volume = part_volume(p);
    if (!(p.volume > 0) || p.points.size() < 4) return {part};
  }
  return pieces;
}

bool hulls_apart(const std::vector<Vec3>& a, const std::vector<Vec3>& b, Real gap) {
  if (a.empty() || b.empty()) return true;
  // Gilbert's iteration (1966) towards the point of the hulls' difference A - B nearest the
  // origin: each step moves x to the point nearest the origin on the segment from x to the
  // difference's extreme point against x. Once the extreme point itself is more than the gap
  // along x, the plane normal to x separates the hulls.
  Vec3 x = mean_of(a) - mean_of(b);
  for (int step = 0; step < 1000; ++step) {
    const Real norm = x.norm();
    if (!(norm > gap)) return false;
    size_t low = 0, high = 0;
    for (size_t i = 1; i < a.size(); ++i)
      if (x.dot(a[i]) < x.dot(a[low])) low = i;
    for (size_t i = 1; i < b.size(); ++i)
      if (x.dot(b[i]) > x.dot(b[high])) high = i;
    const Vec3 extreme = a[low] - b[high];
    if (x.dot(extreme) > gap * norm) return true;
    const Vec3 d = extreme - x;
    const Real t = std::clamp(-x.dot(d) / d.squaredNorm(), Real(0), Real(1));
    if (!(t > 0)) return false;
    x += t * d;
  }
  return false;
}

std::vector<MeshPart> separate_groups(const MeshPart& part, Real smallest_volume, Real gap) {
  std::vector<MeshPart> groups = connected_components(part);
  auto join = [&](size_t into, size_t from) {
    append(groups[into], groups[from]);
    groups.erase(groups.begin() + static_cast<long>(from));
  };
  for (bool changed = true; changed && groups.size() > 1;) {
    changed = false;
    // The smallest piece under the limit joins the group whose corners' mean is nearest.
    size_t small = groups.size();
    for (size_t i = 0; i < groups.size(); ++i)
      if (groups[i].volume < smallest_volume &&
          (small == groups.size() || groups[i].volume < groups[small].volume))
        small = i;
    if (small < groups.size()) {
      const Vec3 at = mean_of(groups[small].points);
      size_t nearest = small == 0 ? 1 : 0;
      for (size_t i = 0; i < groups.size(); ++i)
        if (i != small && (mean_of(groups[i].points) - at).squaredNorm() <
                              (mean_of(groups[nearest].points) - at).squaredNorm())
          nearest = i;
      join(std::min(small, nearest), std::max(small, nearest));
      changed = true;
      continue;
    }
    for (size_t i = 0; i < groups.size() && !changed; ++i)
      for (size_t j = i + 1; j < groups.size() && !changed; ++j)
        if (!hulls_apart(groups[i].points, groups[j].points, gap)) {
          join(i, j);
          changed = true;
        }
  }
  return groups;
}

}  // namespace tem
