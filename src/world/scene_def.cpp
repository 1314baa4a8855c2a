// Rotation matrices of the scene's orientation conventions (include/tem/scene_def.hpp). All are
// active and right-handed: they turn vectors, not frames, so g maps body axes to world axes.
#include "tem/scene_def.hpp"

#include <cmath>

namespace tem {

Mat3 rotation_x(Real angle) {
  const Real c = std::cos(angle);
  const Real s = std::sin(angle);
  Mat3 r;
  r << 1, 0, 0,  //
      0, c, -s,  //
      0, s, c;
  return r;
}

Mat3 rotation_z(Real angle) {
  const Real c = std::cos(angle);
  const Real s = std::sin(angle);
  Mat3 r;
  r << c, -s, 0,  //
      s, c, 0,    //
      0, 0, 1;
  return r;
}

// Goldstein's z-x-z convention read as successive rotations about the body's own axes: first
// phi about z, then theta about the new x, then psi about the newest z. As one active rotation
// from body to world that is the product below, applied right to left.
Mat3 euler_zxz(Real phi, Real theta, Real psi) {
  return rotation_z(phi) * rotation_x(theta) * rotation_z(psi);
}

}  // namespace tem
