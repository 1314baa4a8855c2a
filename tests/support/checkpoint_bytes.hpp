// Checkpoints of older versions for tests that check they are still read: made from a new one by
// taking its newest records away, setting the version field and summing the bytes again.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "support/fnv1a.hpp"

namespace tem::testing_support {

// The whole file, checksum included.
inline std::string checkpoint_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Writes `bytes` (a checkpoint without its checksum) to `path` as version `version`: the field
// after the 8-byte magic set, and the FNV-1a sum of it all appended, as io/checkpoint.cpp does.
inline void write_checkpoint_bytes(const std::string& path, std::string bytes,
                                   std::uint32_t version) {
  std::memcpy(&bytes[8], &version, sizeof version);
  const std::uint64_t h = fnv1a(bytes.data(), bytes.size());
  bytes.append(reinterpret_cast<const char*>(&h), sizeof h);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace tem::testing_support
