#include "tem/mesh_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "io/mesh_blocks_vtu.hpp"
#include "mesh/mesh_body.hpp"

namespace tem {

MeshReport report_mesh(const std::string& file, MeshCutting cutting, int max_blocks, Real scale,
                       const std::string& blocks_vtu) {
  std::shared_ptr<const MeshBody> mesh;
  try {
    mesh = load_mesh_body(file, scale, cutting, max_blocks);
  } catch (const std::exception& e) {
    throw MeshLoadError(e.what());
  }
  const MeshDecomposition& cut = mesh->decomposition;
  std::vector<Block> blocks;
  try {
    for (const PolyhedronDef& def : cut.blocks) blocks.emplace_back(def);
  } catch (const GeometryError& e) {
    throw std::runtime_error(file + ": block " + std::to_string(blocks.size() + 1) + " of " +
                             std::to_string(cut.blocks.size()) + ": " + e.what());
  }

  MeshReport r;
  r.file = file;
  r.vertices = mesh->check.vertices;
  r.faces = mesh->check.faces;
  r.closed = mesh->check.closed;
  r.turned = mesh->check.turned;
  r.volume = mesh->check.volume;
  r.cutting = cutting;
  r.max_blocks = max_blocks;
  r.blocks = static_cast<int>(blocks.size());
  r.blocks_volume = cut.blocks_volume;
  r.smallest_block_volume = blocks.empty() ? 0 : blocks.front().volume();
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Block& b : blocks) {
    r.smallest_block_volume = std::min(r.smallest_block_volume, b.volume());
    lo = lo.cwiseMin(b.bounds_min() + b.centroid_in_input());
    hi = hi.cwiseMax(b.bounds_max() + b.centroid_in_input());
  }
  r.diagonal = (hi - lo).norm();
  r.over_coverage = cut.over_coverage;
  r.hausdorff = cut.hausdorff;
  r.merged_slivers = cut.merged_slivers;
  r.reflex_edges = cut.reflex_edges;
  r.parts = cut.parts;
  r.recut_pieces = cut.recut_pieces;
  r.read_seconds = mesh->read_seconds;
  r.cut_seconds = cut.seconds;
  r.warnings = mesh->check.warnings;
  r.warnings.insert(r.warnings.end(), cut.warnings.begin(), cut.warnings.end());

  if (!blocks_vtu.empty()) {
    std::ofstream out(blocks_vtu, std::ios::binary);
    out << mesh_blocks_vtu(blocks);
    out.close();
    if (!out) throw std::runtime_error(blocks_vtu + ": cannot be written");
  }
  return r;
}

}  // namespace tem
