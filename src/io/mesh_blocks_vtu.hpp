// The convex blocks cut from a mesh as one ParaView file (`tem mesh --out blocks.vtu`): every
// block's surface triangles, with the cell data `block` (1 to N, as in messages) and `volume`
// (of the block the triangle belongs to), so that ParaView colours each block on its own.
#pragma once

#include <string>
#include <vector>

#include "geometry/block.hpp"

namespace tem {

// The file's bytes (binary VTK XML, vtu_binary.hpp). Each block's nodes are placed back in the
// mesh's frame (node + centroid_in_input()).
std::string mesh_blocks_vtu(const std::vector<Block>& blocks);

}  // namespace tem
