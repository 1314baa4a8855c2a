#include "forces/semm_newton/newton_rows.hpp"

#include <algorithm>
#include <cmath>

namespace tem::newton {
namespace {

// A disc of radius r in `dim` dimensions, with proximal centre c: the Coulomb limit of a
// patch's friction, twist or rolling resistance.
RowResponse disc(const Row& row, const Vec2& u) {
  RowResponse out;
  const Real r = row.radius, reg = row.regularisation;
  if (!(r > 0)) return out;  // no normal load: no friction
  Vec2 v = row.centre - u / reg;
  if (row.dim == 1) v.y() = 0;
  const Real size = size_of(row, v);
  if (size <= r || row.held) {  // stick
    out.impulse = v;
    out.curvature.topLeftCorner(row.dim, row.dim).diagonal().setConstant(1 / reg);
  } else {  // slip: on the rim, curvature only across it (none in one dimension)
    const Vec2 direction = v / size;
    out.impulse = r * direction;
    if (row.dim == 2)
      out.curvature = r / (size * reg) * (Mat2::Identity() - direction * direction.transpose());
  }
  out.value = -out.impulse.dot(u) - reg / 2 * (out.impulse - row.centre).squaredNorm();
  return out;
}

}  // namespace

RowResponse respond(const Row& row, const Vec2& u, Real band) {
  if (row.kind != Row::Kind::normal) return disc(row, u);
  RowResponse out;
  // How far the row is from its target, less what its last impulse already answers.
  const Real short_by = row.target - u.x() + row.centre.x() * row.regularisation;
  if (short_by > 0) {
    out.impulse.x() = short_by / row.regularisation;
    out.value = short_by * short_by / (2 * row.regularisation);
  }
  if (short_by > 0 || (band >= 0 && short_by >= -band))
    out.curvature(0, 0) = 1 / row.regularisation;
  return out;
}

}  // namespace tem::newton
