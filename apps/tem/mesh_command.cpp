// `tem mesh`: reads a mesh file, checks it, cuts it into convex blocks and says how well the
// blocks stand for the mesh, for a person (text) or a script (--json); --out writes the blocks
// for ParaView. The scene's `mesh` shape is cut the same way (tem/mesh_report.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "tem/mesh_report.hpp"

namespace tem::cli {
namespace {

// The blocks' volume against the mesh's, relative; 0 when both are 0.
Real relative(Real value, Real reference) {
  return reference == 0 ? std::abs(value) : std::abs(value - reference) / std::abs(reference);
}

}  // namespace

int mesh_command(const std::string& mesh_file, const std::string& cutting_name, int max_blocks,
                 Real scale, const std::string& out_file, bool json) {
  const MeshCutting cutting =
      cutting_name == "exact" ? MeshCutting::exact : MeshCutting::approximate;
  MeshReport r;
  try {
    r = report_mesh(mesh_file, cutting, max_blocks, scale, out_file);
  } catch (const MeshLoadError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return kExitFailed;
  }
  for (const std::string& w : r.warnings) std::cerr << mesh_file << ": warning: " << w << "\n";
  const double seconds = r.read_seconds + r.cut_seconds;

  const char* cutting_text = cutting == MeshCutting::exact ? "exact" : "approximate";
  // The figures a user weighs max_blocks by: over-coverage against the mesh's volume, the
  // Hausdorff distance against the bounding-box diagonal (the blocks' box is the mesh's: they
  // cover the mesh and each is the hull of a part of it).
  const Real over_coverage_percent = 100 * r.over_coverage / r.volume;
  const Real hausdorff_percent = 100 * r.hausdorff / r.diagonal;
  if (json) {
    nlohmann::ordered_json j = {
        {"file", mesh_file},
        {"vertices", r.vertices},
        {"faces", r.faces},
        {"closed", r.closed},
        {"turned", r.turned},
        {"volume", r.volume},
        {"cutting", cutting_text},
        {"blocks", r.blocks},
        {"blocks_volume", r.blocks_volume},
        {"volume_error", relative(r.blocks_volume, r.volume)},
        {"smallest_block_volume", r.smallest_block_volume},
        {"over_coverage", r.over_coverage},
        {"over_coverage_percent", over_coverage_percent},
        {"hausdorff", r.hausdorff},
        {"hausdorff_percent", hausdorff_percent},
        {"diagonal", r.diagonal},
        {"merged_slivers", r.merged_slivers},
        {"reflex_edges", r.reflex_edges},
        {"parts", r.parts},
        {"recut_pieces", r.recut_pieces},
        {"read_seconds", r.read_seconds},
        {"cut_seconds", r.cut_seconds},
        {"seconds", seconds}};
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  std::printf("%s\n", mesh_file.c_str());
  std::printf("  vertices %d, faces %d, %s%s\n", r.vertices, r.faces,
              r.closed ? "closed" : "open",
              r.turned ? " (all faces pointed inwards: turned)" : "");
  std::printf("  volume              %.10g (from the surface)\n", r.volume);
  std::printf("  read and checked in %.3g s\n", r.read_seconds);
  std::printf("  cut %s into %d block%s in %.3g s%s\n", cutting_text, r.blocks,
              r.blocks == 1 ? "" : "s", r.cut_seconds,
              cutting == MeshCutting::approximate
                  ? (" (at most " + std::to_string(max_blocks) + ")").c_str()
                  : "");
  std::printf("  blocks' volume      %.10g (relative difference %.3g)\n", r.blocks_volume,
              relative(r.blocks_volume, r.volume));
  std::printf("  smallest block      %.4g of the mesh's volume\n",
              r.smallest_block_volume / r.volume);
  if (cutting == MeshCutting::approximate) {
    std::printf("  over-coverage       %.4g (%.3g %% of the mesh's volume)\n", r.over_coverage,
                over_coverage_percent);
    std::printf("  Hausdorff distance  %.4g (%.3g %% of the bounding-box diagonal)\n",
                r.hausdorff, hausdorff_percent);
  }
  if (cutting == MeshCutting::exact)
    std::printf("  reflex edges        %d (CGAL cut %s)\n", r.reflex_edges,
                r.parts == 1 ? "the mesh whole"
                               : ("the " + std::to_string(r.parts) + " parts of the mesh one at a "
                                  "time").c_str());
  if (r.merged_slivers > 0) std::printf("  slivers merged      %d\n", r.merged_slivers);
  if (r.recut_pieces > 0)
    std::printf("  pieces re-cut       %d (into tetrahedra: no hull made a block of them)\n",
                r.recut_pieces);
  if (!out_file.empty())
    std::printf("  wrote %s (cell data 'block' = 1..%d)\n", out_file.c_str(), r.blocks);
  std::cout.flush();
  return kExitOk;
}

}  // namespace tem::cli
