#include "mass/mass_properties.hpp"

namespace tem {

MassProperties block_mass_properties(const Block& block, Real density) {
  MassProperties m;
  m.volume = block.volume();
  m.mass = density * block.volume();
  m.center = Vec3::Zero();  // nodes are stored about the block's centroid
  m.second_moment = density * block.second_moment();
  return m;
}

MassProperties combine(const std::vector<PlacedMass>& parts) {
  MassProperties total;
  Vec3 first_moment = Vec3::Zero();
  for (const PlacedMass& p : parts) {
    total.volume += p.mass.volume;
    total.mass += p.mass.mass;
    first_moment += p.mass.mass * (p.rotation * p.mass.center + p.position);
  }
  if (total.mass > 0) total.center = first_moment / total.mass;
  for (const PlacedMass& p : parts) {
    const Vec3 t = p.rotation * p.mass.center + p.position - total.center;
    total.second_moment += p.rotation * p.mass.second_moment * p.rotation.transpose() +
                           p.mass.mass * t * t.transpose();
  }
  // R S R^T is symmetric only up to round-off; the tensor is symmetric by definition.
  total.second_moment = 0.5 * (total.second_moment + total.second_moment.transpose()).eval();
  return total;
}

}  // namespace tem
