// The message of the MeshError that check_mesh() throws for a mesh, for tests of refusals.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "mesh/mesh_check.hpp"

namespace tem::testing_support {

// Fails the calling test (and returns "") when check_mesh() accepts the mesh.
inline std::string check_error(TriangleMesh mesh) {
  try {
    check_mesh(mesh);
  } catch (const MeshError& e) {
    return e.what();
  }
  ADD_FAILURE() << "check_mesh accepted " << mesh.source;
  return "";
}

}  // namespace tem::testing_support
