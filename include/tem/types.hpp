// Basic numeric types shared by every part of TEM: one Real (double) everywhere, and Eigen's
// fixed-size vectors and matrices for the 3-D algebra of the paper.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tem {

using Real = double;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;
using Quat = Eigen::Quaternion<Real>;

// R(a) of eq. 11: the matrix with R(a) b = a x b.
inline Mat3 cross_matrix(const Vec3& a) {
  Mat3 r;
  r << 0, -a.z(), a.y(),  //
      a.z(), 0, -a.x(),   //
      -a.y(), a.x(), 0;
  return r;
}

// The Cayley transform cay(R(a)) = (I - R(a)/2)^-1 (I + R(a)/2)
// = I + 4/(4 + |a|^2) (R(a) + R(a)^2/2), from R(a)^3 = -|a|^2 R(a): a rotation to round-off for
// every a, close to the rotation by |a| about a for small a.
inline Mat3 cayley(const Vec3& a) {
  const Mat3 w = cross_matrix(a);
  return Mat3::Identity() + (4 / (4 + a.squaredNorm())) * (w + 0.5 * w * w);
}

}  // namespace tem
