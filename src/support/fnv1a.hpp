// FNV-1a, 64 bits: the checksum of checkpoints and the content hash of the files a scene reads.
// Not cryptographic; it tells a changed or damaged file from the one that was read.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tem {

inline std::uint64_t fnv1a(const char* data, std::size_t size) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace tem
