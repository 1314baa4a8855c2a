#include "io/mesh_blocks_vtu.hpp"

#include "io/vtu_binary.hpp"

namespace tem {

std::string mesh_blocks_vtu(const std::vector<Block>& blocks) {
  std::vector<Vec3> points;
  std::vector<std::int64_t> connectivity;
  std::vector<int> block_ids;
  std::vector<Real> volumes;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    const std::int64_t first = static_cast<std::int64_t>(points.size());
    for (const Vec3& node : block.nodes()) points.push_back(node + block.centroid_in_input());
    for (const Triangle& t : block.triangles()) {
      for (int node : t.nodes) connectivity.push_back(first + node);
      block_ids.push_back(static_cast<int>(b) + 1);
      volumes.push_back(block.volume());
    }
  }
  VtuBinary vtu(0.0, points.size(), block_ids.size());
  vtu.begin_cell_data();
  vtu.ints("block", block_ids);
  vtu.reals("volume", volumes);
  vtu.end_cell_data();
  vtu.points(points);
  vtu.cells(connectivity, 3, kVtkTriangle);
  return vtu.finish();
}

}  // namespace tem
