// `tem mesh`: reads a mesh file, checks it, cuts it into convex blocks and says how well the
// blocks stand for the mesh, for a person (text) or a script (--json); --out writes the blocks
// for ParaView. The scene's `mesh` shape goes through the same load_mesh_body().
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "io/mesh_blocks_vtu.hpp"
#include "mesh/mesh_body.hpp"

namespace tem::cli {
namespace {

// The blocks' volume against the mesh's, relative; 0 when both are 0.
Real relative(Real value, Real reference) {
  return reference == 0 ? std::abs(value) : std::abs(value - reference) / std::abs(reference);
}

struct BlocksFigures {
  Real smallest_volume = 0;
  Real diagonal = 0;  // of the mesh's bounding box
};

}  // namespace

int mesh_command(const std::string& mesh_file, const std::string& cutting_name, int max_blocks,
                 Real scale, const std::string& out_file, bool json) {
  const MeshCutting cutting =
      cutting_name == "exact" ? MeshCutting::exact : MeshCutting::approximate;
  std::shared_ptr<const MeshBody> mesh;
  try {
    mesh = load_mesh_body(mesh_file, scale, cutting, max_blocks);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  for (const std::string& w : mesh->check.warnings) std::cerr << mesh_file << ": warning: " << w << "\n";
  const MeshDecomposition& cut = mesh->decomposition;
  for (const std::string& w : cut.warnings) std::cerr << mesh_file << ": warning: " << w << "\n";

  std::vector<Block> blocks;
  try {
    for (const PolyhedronDef& def : cut.blocks) blocks.emplace_back(def);
  } catch (const GeometryError& e) {
    std::cerr << mesh_file << ": block " << blocks.size() + 1 << " of " << cut.blocks.size()
              << ": " << e.what() << "\n";
    return kExitFailed;
  }
  BlocksFigures figures;
  figures.smallest_volume = blocks.empty() ? 0 : blocks.front().volume();
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Block& b : blocks) {
    figures.smallest_volume = std::min(figures.smallest_volume, b.volume());
    lo = lo.cwiseMin(b.bounds_min() + b.centroid_in_input());
    hi = hi.cwiseMax(b.bounds_max() + b.centroid_in_input());
  }
  figures.diagonal = (hi - lo).norm();
  const double seconds = mesh->read_seconds + cut.seconds;

  if (!out_file.empty()) {
    std::ofstream out(out_file, std::ios::binary);
    out << mesh_blocks_vtu(blocks);
    out.close();
    if (!out) {
      std::cerr << out_file << ": cannot be written\n";
      return kExitFailed;
    }
  }

  const char* cutting_text = cutting == MeshCutting::exact ? "exact" : "approximate";
  // The figures a user weighs max_blocks by: over-coverage against the mesh's volume, the
  // Hausdorff distance against the bounding-box diagonal (the blocks' box is the mesh's: they
  // cover the mesh and each is the hull of a part of it).
  const Real over_coverage_percent = 100 * cut.over_coverage / mesh->check.volume;
  const Real hausdorff_percent = 100 * cut.hausdorff / figures.diagonal;
  if (json) {
    nlohmann::ordered_json j = {
        {"file", mesh_file},
        {"vertices", mesh->check.vertices},
        {"faces", mesh->check.faces},
        {"closed", mesh->check.closed},
        {"turned", mesh->check.turned},
        {"volume", mesh->check.volume},
        {"cutting", cutting_text},
        {"blocks", blocks.size()},
        {"blocks_volume", cut.blocks_volume},
        {"volume_error", relative(cut.blocks_volume, mesh->check.volume)},
        {"smallest_block_volume", figures.smallest_volume},
        {"over_coverage", cut.over_coverage},
        {"over_coverage_percent", over_coverage_percent},
        {"hausdorff", cut.hausdorff},
        {"hausdorff_percent", hausdorff_percent},
        {"diagonal", figures.diagonal},
        {"merged_slivers", cut.merged_slivers},
        {"reflex_edges", cut.reflex_edges},
        {"parts", cut.parts},
        {"recut_pieces", cut.recut_pieces},
        {"read_seconds", mesh->read_seconds},
        {"cut_seconds", cut.seconds},
        {"seconds", seconds}};
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  std::printf("%s\n", mesh_file.c_str());
  std::printf("  vertices %d, faces %d, %s%s\n", mesh->check.vertices, mesh->check.faces,
              mesh->check.closed ? "closed" : "open",
              mesh->check.turned ? " (all faces pointed inwards: turned)" : "");
  std::printf("  volume              %.10g (from the surface)\n", mesh->check.volume);
  std::printf("  read and checked in %.3g s\n", mesh->read_seconds);
  std::printf("  cut %s into %zu block%s in %.3g s%s\n", cutting_text, blocks.size(),
              blocks.size() == 1 ? "" : "s", cut.seconds,
              cutting == MeshCutting::approximate
                  ? (" (at most " + std::to_string(max_blocks) + ")").c_str()
                  : "");
  std::printf("  blocks' volume      %.10g (relative difference %.3g)\n", cut.blocks_volume,
              relative(cut.blocks_volume, mesh->check.volume));
  std::printf("  smallest block      %.4g of the mesh's volume\n",
              figures.smallest_volume / mesh->check.volume);
  if (cutting == MeshCutting::approximate) {
    std::printf("  over-coverage       %.4g (%.3g %% of the mesh's volume)\n", cut.over_coverage,
                over_coverage_percent);
    std::printf("  Hausdorff distance  %.4g (%.3g %% of the bounding-box diagonal)\n",
                cut.hausdorff, hausdorff_percent);
  }
  if (cutting == MeshCutting::exact)
    std::printf("  reflex edges        %d (CGAL cut %s)\n", cut.reflex_edges,
                cut.parts == 1 ? "the mesh whole"
                               : ("the " + std::to_string(cut.parts) + " parts of the mesh one at a "
                                  "time").c_str());
  if (cut.merged_slivers > 0) std::printf("  slivers merged      %d\n", cut.merged_slivers);
  if (cut.recut_pieces > 0)
    std::printf("  pieces re-cut       %d (into tetrahedra: no hull made a block of them)\n",
                cut.recut_pieces);
  if (!out_file.empty())
    std::printf("  wrote %s (cell data 'block' = 1..%zu)\n", out_file.c_str(), blocks.size());
  std::cout.flush();
  return kExitOk;
}

}  // namespace tem::cli
