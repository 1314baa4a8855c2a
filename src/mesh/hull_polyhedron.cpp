// Convex hulls of mesh parts by Qhull (reentrant C library, as geometry/convex_hull.cpp uses
// it). convex_hull() there refuses interior points and trusts Qhull's facets; a part's points
// are mostly interior, and hulls of dense scans have short edges and nearly flat corners that
// Block's relative tolerance refuses, hence the welding and the check-and-retry here.
#include "mesh/hull_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>

extern "C" {
#include <libqhull_r/libqhull_r.h>
#include <libqhull_r/geom_r.h>
}

namespace tem {
namespace {

// Block's relative tolerance (block.cpp); the checks here use a tenth of it where Block
// compares against it, and ten times it where Block requires more than it.
constexpr Real kBlockTolerance = 1e-9;
// Rounds of dropping flawed vertices before a hull is given up (a few suffice in practice).
constexpr int kMaxRounds = 50;

// One Qhull run on points taken about their mean; frees its memory however it ended.
class QhullRun {
 public:
  // options: Qhull's command line, "qhull ..."
  QhullRun(const std::vector<Vec3>& points, const char* options) {
    qh_zero(&qh_, nullptr);
    for (const Vec3& p : points) mean_ += p;
    mean_ /= static_cast<Real>(std::max<size_t>(points.size(), 1));
    coords_.reserve(points.size() * 3);
    for (const Vec3& p : points)
      for (int k = 0; k < 3; ++k) coords_.push_back(p[k] - mean_[k]);
    if (points.size() < 4) return;
    messages_ = open_memstream(&message_text_, &message_size_);  // Qhull's complaints, unread
    std::string command(options);
    ok_ = qh_new_qhull(&qh_, 3, static_cast<int>(points.size()), coords_.data(), False,
                       command.data(), nullptr, messages_) == 0;
  }
  ~QhullRun() {
    qh_freeqhull(&qh_, !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(&qh_, &curlong, &totlong);
    if (messages_) std::fclose(messages_);
    std::free(message_text_);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  bool ok() const { return ok_; }
  qhT* qh() { return &qh_; }
  int id(const vertexT* v) { return qh_pointid(&qh_, v->point); }

 private:
  qhT qh_;
  Vec3 mean_ = Vec3::Zero();
  std::vector<coordT> coords_;
  FILE* messages_ = nullptr;
  char* message_text_ = nullptr;
  size_t message_size_ = 0;
  bool ok_ = false;
};


// One point per `weld`-sized neighbourhood, the first in input order.
std::vector<Vec3> welded(const std::vector<Vec3>& points, Real weld) {
  struct KeyHash {
    size_t operator()(const std::array<long long, 3>& k) const {
      return static_cast<size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<int>, KeyHash> grid;
  std::vector<Vec3> kept;
  for (const Vec3& p : points) {
    const std::array<long long, 3> cell{std::llround(std::floor(p.x() / weld)),
                                        std::llround(std::floor(p.y() / weld)),
                                        std::llround(std::floor(p.z() / weld))};
    bool near = false;
    for (long long dx = -1; dx <= 1 && !near; ++dx)
      for (long long dy = -1; dy <= 1 && !near; ++dy)
        for (long long dz = -1; dz <= 1 && !near; ++dz) {
          const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (int other : it->second)
            if ((kept[other] - p).norm() < weld) near = true;
        }
    if (near) continue;
    grid[cell].push_back(static_cast<int>(kept.size()));
    kept.push_back(p);
  }
  return kept;
}

// The vertices that would make Block refuse the polyhedron (or come close to it), by Block's
// own measures: size about the mean of the points, Newell normals, planes through the loops'
// centres. Nothing when the polyhedron is too flat to be a block at all.
std::optional<std::vector<bool>> flawed_vertices(const PolyhedronDef& def, Real margin) {
  const std::vector<Vec3>& pts = def.points;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : pts) mean += p;
  mean /= static_cast<Real>(pts.size());
  Real size = 0;
  for (const Vec3& p : pts) size = std::max(size, (p - mean).norm());
  const Real strict = margin * kBlockTolerance * size, flat = kBlockTolerance * size / margin;

  Real volume = 0;
  for (const auto& loop : def.polygons)
    for (size_t i = 1; i + 1 < loop.size(); ++i)
      volume += (pts[loop[0]] - mean).dot((pts[loop[i]] - mean).cross(pts[loop[i + 1]] - mean)) / 6;
  if (!(volume > strict * size * size)) return std::nullopt;

  std::vector<bool> flawed(pts.size(), false);
  for (const auto& loop : def.polygons) {
    const size_t m = loop.size();
    Vec3 n = Vec3::Zero(), centre = Vec3::Zero();
    for (size_t i = 0; i < m; ++i) centre += pts[loop[i]];
    for (size_t i = 1; i + 1 < m; ++i)  // Block's Newell normal, about the first corner
      n += (pts[loop[i]] - pts[loop[0]]).cross(pts[loop[i + 1]] - pts[loop[0]]);
    centre /= static_cast<Real>(m);
    auto turn = [&](size_t i, const Vec3& normal) {
      const Vec3& a = pts[loop[i]];
      const Vec3& b = pts[loop[(i + 1) % m]];
      const Vec3& c = pts[loop[(i + 2) % m]];
      return (b - a).cross(c - b).dot(normal);
    };
    if (n.norm() <= strict * size) {  // a sliver: drop its flattest corner
      size_t flattest = 0;
      for (size_t i = 1; i < m; ++i)
        if (std::abs(turn(i, n)) < std::abs(turn(flattest, n))) flattest = i;
      flawed[loop[(flattest + 1) % m]] = true;
      continue;
    }
    n.normalize();
    size_t farthest = 0;
    for (size_t i = 1; i < m; ++i)
      if (std::abs(n.dot(pts[loop[i]] - centre)) > std::abs(n.dot(pts[loop[farthest]] - centre)))
        farthest = i;
    if (std::abs(n.dot(pts[loop[farthest]] - centre)) > flat) flawed[loop[farthest]] = true;
    for (size_t i = 0; i < m; ++i)
      if (turn(i, n) <= strict * size) flawed[loop[(i + 1) % m]] = true;
    const Real offset = n.dot(centre);
    for (size_t p = 0; p < pts.size(); ++p)
      if (n.dot(pts[p]) - offset > flat) flawed[p] = true;
  }
  return flawed;
}

}  // namespace

std::optional<PolyhedronDef> hull_polyhedron(const std::vector<Vec3>& points) {
  QhullRun hull(points, "qhull");  // merges coplanar facets into polygons
  if (!hull.ok()) return std::nullopt;
  qhT* qh = hull.qh();
  std::vector<int> new_index(points.size(), -1);
  for (vertexT* v = qh->vertex_list; v && v->next; v = v->next) new_index[hull.id(v)] = 0;
  PolyhedronDef def;
  for (size_t i = 0; i < points.size(); ++i)
    if (new_index[i] == 0) {
      new_index[i] = static_cast<int>(def.points.size());
      def.points.push_back(points[i]);
    }
  for (facetT* f = qh->facet_list; f && f->next; f = f->next) {
    const Vec3 n(f->normal[0], f->normal[1], f->normal[2]);
    std::vector<int> loop;
    Vec3 centre = Vec3::Zero();
    const int count = qh_setsize(qh, f->vertices);
    for (int k = 0; k < count; ++k) {
      loop.push_back(new_index[hull.id(static_cast<vertexT*>(SETelem_(f->vertices, k)))]);
      centre += def.points[loop.back()];
    }
    centre /= static_cast<Real>(count);
    const Vec3 u = (def.points[loop[0]] - centre).normalized();
    const Vec3 w = n.cross(u);
    std::vector<std::pair<Real, int>> by_angle;
    for (int id : loop) {
      const Vec3 d = def.points[id] - centre;
      by_angle.emplace_back(std::atan2(d.dot(w), d.dot(u)), id);
    }
    std::sort(by_angle.begin(), by_angle.end());
    for (size_t k = 0; k < loop.size(); ++k) loop[k] = by_angle[k].second;
    def.polygons.push_back(std::move(loop));
  }
  return def;
}

Real hull_volume(const std::vector<Vec3>& points) {
  // Joggled input (a fixed seed: the same volume every run) spares Qhull its merging, which
  // takes half of its time on the many coplanar points of cut parts; the volume moves by about
  // 1e-11 of the part's size, far below what ranking cuts needs.
  QhullRun hull(points, "qhull QJ QR-7");
  if (!hull.ok()) return 0;
  qh_getarea(hull.qh(), hull.qh()->facet_list);
  return hull.qh()->totvol;
}

std::optional<PolyhedronDef> hull_block(const std::vector<Vec3>& points, Real weld, Real margin) {
  // Only the hull's vertices matter; weld those (far fewer than the points).
  std::optional<PolyhedronDef> def = hull_polyhedron(points);
  if (!def) return std::nullopt;
  std::vector<Vec3> kept = welded(def->points, weld);
  for (int round = 0; round < kMaxRounds; ++round) {
    def = hull_polyhedron(kept);
    if (!def) return std::nullopt;
    const auto flawed = flawed_vertices(*def, margin);
    if (!flawed) return std::nullopt;
    if (std::find(flawed->begin(), flawed->end(), true) == flawed->end()) {
      try {
        Block check(*def);  // the final word is Block's
        return def;
      } catch (const GeometryError&) {
        return std::nullopt;
      }
    }
    kept.clear();
    for (size_t i = 0; i < def->points.size(); ++i)
      if (!(*flawed)[i]) kept.push_back(def->points[i]);
  }
  return std::nullopt;
}

Real radius_about_mean(const std::vector<Vec3>& points) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<Real>(std::max<size_t>(points.size(), 1));
  Real radius = 0;
  for (const Vec3& p : points) radius = std::max(radius, (p - mean).norm());
  return radius;
}

}  // namespace tem
