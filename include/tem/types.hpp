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

}  // namespace tem
