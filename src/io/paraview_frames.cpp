#include "io/paraview_frames.hpp"

#include "collision/block_pose.hpp"
#include "io/vtu_binary.hpp"

namespace tem {

std::string bodies_vtu(const Model& model, const State& state, const std::vector<char>* only) {
  size_t point_count = 0, triangle_count = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    for (const BlockInstance& instance : model.bodies[b].blocks) {
      if (only && !(*only)[b]) continue;
      point_count += model.blocks[instance.block].nodes().size();
      triangle_count += model.blocks[instance.block].triangles().size();
    }

  std::vector<Vec3> points, velocities, angular_velocities;
  points.reserve(point_count);
  velocities.reserve(point_count);
  angular_velocities.reserve(point_count);
  std::vector<std::int64_t> connectivity;
  connectivity.reserve(3 * triangle_count);
  std::vector<int> body_ids, block_ids;
  body_ids.reserve(triangle_count);
  block_ids.reserve(triangle_count);

  int block_id = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (only && !(*only)[b]) {
      block_id += static_cast<int>(model.bodies[b].blocks.size());
      continue;
    }
    const BodyState& s = state.bodies[b];
    const Vec3 w = s.angular_velocity_world();
    // The body's stable id (its index unless bodies have come or gone), so that ParaView can
    // follow one body from frame to frame.
    const int body_id =
        b < state.tags.size() ? static_cast<int>(state.tags[b].id) : static_cast<int>(b);
    for (const BlockInstance& instance : model.bodies[b].blocks) {
      const Block& block = model.blocks[instance.block];
      const BlockPose pose = block_pose(instance, s);
      const auto first = static_cast<std::int64_t>(points.size());
      for (const Vec3& node : block.nodes()) {
        const Vec3 p = pose.to_world(node);
        points.push_back(p);
        velocities.push_back(s.v + w.cross(p - s.x));
        angular_velocities.push_back(w);
      }
      for (const Triangle& t : block.triangles()) {
        for (int k = 0; k < 3; ++k) connectivity.push_back(first + t.nodes[k]);
        body_ids.push_back(body_id);
        block_ids.push_back(block_id);
      }
      ++block_id;
    }
  }

  VtuBinary vtu(state.time, points.size(), body_ids.size());
  vtu.begin_point_data();
  vtu.vectors("velocity", velocities);
  vtu.vectors("angular_velocity", angular_velocities);
  vtu.end_point_data();
  vtu.begin_cell_data();
  vtu.ints("body_id", body_ids);
  vtu.ints("block_id", block_ids);
  vtu.end_cell_data();
  vtu.points(points);
  vtu.cells(connectivity, 3, kVtkTriangle);
  return vtu.finish();
}

std::string contacts_vtu(Real time, const std::vector<ContactPatch>& patches,
                         const std::vector<PatchForce>& forces) {
  const size_t n = patches.size();
  std::vector<Vec3> points(n), normals(n), force(n);
  std::vector<Real> depth(n), fn(n), ft(n);
  std::vector<int> body_a(n), body_b(n), wall(n);
  std::vector<std::int64_t> connectivity(n);
  for (size_t i = 0; i < n; ++i) {
    const ContactPatch& p = patches[i];
    const PatchForce f = forces.empty() ? PatchForce{} : forces[i];
    points[i] = p.point;
    normals[i] = p.normal;
    depth[i] = p.depth;
    fn[i] = f.normal;
    ft[i] = f.tangential;
    force[i] = f.normal * p.normal;
    body_a[i] = p.body_a;
    body_b[i] = p.body_b;
    wall[i] = p.wall;
    connectivity[i] = static_cast<std::int64_t>(i);
  }

  VtuBinary vtu(time, n, n);
  vtu.begin_point_data();
  vtu.vectors("normal", normals);
  vtu.reals("depth", depth);
  vtu.reals("fn", fn);
  vtu.reals("ft", ft);
  vtu.vectors("force", force);
  vtu.ints("body_a", body_a);
  vtu.ints("body_b", body_b);
  vtu.ints("wall", wall);
  vtu.end_point_data();
  vtu.points(points);
  vtu.cells(connectivity, 1, kVtkVertex);
  return vtu.finish();
}

namespace {

// A parallel file over `pieces`, declaring their point and cell arrays.
std::string pvtu(const std::string& point_data, const std::string& cell_data,
                 const std::vector<std::string>& pieces) {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData>\n" +
      point_data + "</PPointData>\n<PCellData>\n" + cell_data +
      "</PCellData>\n<PPoints>\n<PDataArray type=\"Float64\" Name=\"Points\" "
      "NumberOfComponents=\"3\"/>\n</PPoints>\n";
  for (const std::string& piece : pieces) text += "<Piece Source=\"" + piece + "\"/>\n";
  return text + "</PUnstructuredGrid>\n</VTKFile>\n";
}

std::string declare(const char* type, const char* name, int components = 1) {
  return std::string("<PDataArray type=\"") + type + "\" Name=\"" + name + "\"" +
         (components > 1 ? " NumberOfComponents=\"" + std::to_string(components) + "\"" : "") +
         "/>\n";
}

}  // namespace

std::string bodies_pvtu(const std::vector<std::string>& pieces) {
  return pvtu(declare("Float64", "velocity", 3) + declare("Float64", "angular_velocity", 3),
              declare("Int32", "body_id") + declare("Int32", "block_id"), pieces);
}

std::string contacts_pvtu(const std::vector<std::string>& pieces) {
  return pvtu(declare("Float64", "normal", 3) + declare("Float64", "depth") +
                  declare("Float64", "fn") + declare("Float64", "ft") +
                  declare("Float64", "force", 3) + declare("Int32", "body_a") +
                  declare("Int32", "body_b") + declare("Int32", "wall"),
              "", pieces);
}

}  // namespace tem
