#include "mesh/mesh_body.hpp"

#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <tuple>

#include "mass/surface_integrals.hpp"
#include "mesh/mesh_reader.hpp"

namespace tem {
namespace {

using CacheKey = std::tuple<std::string, std::uintmax_t, long long, Real, int, int>;

CacheKey cache_key(const std::string& file_path, Real scale, MeshCutting cutting, int max_blocks) {
  std::error_code ec;
  const std::filesystem::path path(file_path);
  const std::string canonical = std::filesystem::weakly_canonical(path, ec).string();
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const auto written = std::filesystem::last_write_time(path, ec);
  return {ec ? file_path : canonical, ec ? 0 : size,
          ec ? 0 : static_cast<long long>(written.time_since_epoch().count()), scale,
          static_cast<int>(cutting), cutting == MeshCutting::approximate ? max_blocks : 0};
}

}  // namespace

std::shared_ptr<const MeshBody> load_mesh_body(const std::string& file_path, Real scale,
                                               MeshCutting cutting, int max_blocks) {
  // Loading holds the lock: two threads asking for one file wait for a single decomposition.
  static std::mutex mutex;
  static std::map<CacheKey, std::shared_ptr<const MeshBody>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  const CacheKey key = cache_key(file_path, scale, cutting, max_blocks);
  if (auto found = cache.find(key); found != cache.end()) return found->second;

  auto body = std::make_shared<MeshBody>();
  body->file_path = file_path;
  body->scale = scale;
  body->cutting = cutting;
  body->max_blocks = max_blocks;
  const auto start = std::chrono::steady_clock::now();
  TriangleMesh mesh = read_mesh_file(file_path, scale, &body->content_hash);
  body->check = check_mesh(mesh);
  body->read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  body->surface = surface_mass_properties(corner_triangles(mesh));
  body->decomposition = cutting == MeshCutting::exact ? exact_decomposition(mesh)
                                                      : approximate_decomposition(mesh, max_blocks);
  if (body->decomposition.blocks.empty())
    throw MeshError(file_path + ": cutting the mesh into convex blocks gave no block");
  cache.emplace(key, body);
  return body;
}

}  // namespace tem
