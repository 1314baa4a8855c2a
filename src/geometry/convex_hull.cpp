// The convex hull of a user's point cloud, by Qhull (reentrant C library). Qhull merges coplanar
// facets by default in 3-d, so each facet is one planar polygon of the block; its vertices come
// unordered and are put in counter-clockwise order about the facet's outward normal here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geometry/block.hpp"

extern "C" {
#include <libqhull_r/libqhull_r.h>
}

namespace tem {
namespace {

// Owns one Qhull run and frees all of its memory however the run ended.
class QhullRun {
 public:
  QhullRun() { qh_zero(&qh_, nullptr); }
  ~QhullRun() {
    qh_freeqhull(&qh_, !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(&qh_, &curlong, &totlong);
    if (errors_) std::fclose(errors_);
    std::free(error_text_);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  // Returns Qhull's exit code; its messages are kept for error reports.
  int run(std::vector<coordT>& coords, char* options) {
    errors_ = open_memstream(&error_text_, &error_size_);
    return qh_new_qhull(&qh_, 3, static_cast<int>(coords.size() / 3), coords.data(), False, options,
                        nullptr, errors_);
  }
  std::string messages() {
    if (errors_) std::fflush(errors_);
    return error_text_ ? std::string(error_text_, error_size_) : std::string();
  }
  qhT* qh() { return &qh_; }

 private:
  qhT qh_;
  FILE* errors_ = nullptr;
  char* error_text_ = nullptr;
  size_t error_size_ = 0;
};

std::string first_line(const std::string& text) {
  const auto start = text.find_first_not_of(" \n");
  if (start == std::string::npos) return "";
  return text.substr(start, text.find('\n', start) - start);
}

}  // namespace

PolyhedronDef convex_hull(const std::vector<Vec3>& points) {
  if (points.size() < 4)
    throw GeometryError("a convex block needs at least 4 points, got " +
                        std::to_string(points.size()));
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) {
    if (!p.allFinite()) throw GeometryError("a point is not finite");
    mean += p;
  }
  mean /= static_cast<Real>(points.size());
  Real size = 0;
  for (const Vec3& p : points) size = std::max(size, (p - mean).norm());
  const Real tol = 1e-9 * size;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      if ((points[i] - points[j]).norm() <= tol)
        throw GeometryError("points " + std::to_string(i) + " and " + std::to_string(j) +
                            " coincide");

  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) coords.push_back(p[k] - mean[k]);

  QhullRun hull;
  char options[] = "qhull";
  const int code = hull.run(coords, options);
  if (code == qh_ERRsingular)
    throw GeometryError("the points are coplanar or collinear: the block has zero volume");
  if (code != 0)
    throw GeometryError("Qhull could not build the hull: " + first_line(hull.messages()));
  qhT* qh = hull.qh();

  // Hull vertices get new, compact indices in input order (deterministic).
  std::vector<int> new_index(points.size(), -1);
  for (vertexT* v = qh->vertex_list; v && v->next; v = v->next)
    new_index[qh_pointid(qh, v->point)] = 0;
  PolyhedronDef def;
  for (size_t i = 0; i < points.size(); ++i)
    if (new_index[i] == 0) {
      new_index[i] = static_cast<int>(def.points.size());
      def.points.push_back(points[i]);
    }

  std::vector<std::pair<Vec3, Real>> planes;  // outward normal, offset (about the mean)
  for (facetT* f = qh->facet_list; f && f->next; f = f->next) {
    const Vec3 n(f->normal[0], f->normal[1], f->normal[2]);
    planes.emplace_back(n, -f->offset);
    // Order the facet's vertices by angle about its centre, seen from outside.
    std::vector<int> loop;
    Vec3 centre = Vec3::Zero();
    const int count = qh_setsize(qh, f->vertices);
    for (int k = 0; k < count; ++k) {
      const int id = qh_pointid(qh, static_cast<vertexT*>(SETelem_(f->vertices, k))->point);
      loop.push_back(id);
      centre += points[id];
    }
    centre /= static_cast<Real>(count);
    const Vec3 u = (points[loop[0]] - centre).normalized();
    const Vec3 w = n.cross(u);
    std::vector<std::pair<Real, int>> by_angle;
    for (int id : loop) {
      const Vec3 d = points[id] - centre;
      by_angle.emplace_back(std::atan2(d.dot(w), d.dot(u)), new_index[id]);
    }
    std::sort(by_angle.begin(), by_angle.end());
    std::vector<int> polygon;
    for (const auto& [angle, id] : by_angle) polygon.push_back(id);
    def.polygons.push_back(std::move(polygon));
  }

  // A point strictly inside the hull would not be a node of the block: the user described a
  // non-convex shape (or a stray point). Points on the surface but not vertices are harmless.
  for (size_t i = 0; i < points.size(); ++i) {
    if (new_index[i] >= 0) continue;
    Real outside = -std::numeric_limits<Real>::infinity();
    const Vec3 p = points[i] - mean;
    for (const auto& [n, offset] : planes) outside = std::max(outside, n.dot(p) - offset);
    if (outside < -tol)
      throw GeometryError("the points do not describe a convex block: point " + std::to_string(i) +
                          " lies inside the hull of the others");
  }
  return def;
}

}  // namespace tem
