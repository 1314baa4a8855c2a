// FNV-1a, 64 bits: the checksum of checkpoints, the content hash of the files a scene reads and
// the state hash (`tem run --hash`). Not cryptographic; it tells a changed or damaged file or
// state from the one that was read.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tem {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;

// Mixes `size` bytes into the running hash `h` (start from kFnv1aOffset).
inline void fnv1a_mix(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 1099511628211ull;
  }
}

inline std::uint64_t fnv1a(const char* data, std::size_t size) {
  std::uint64_t h = kFnv1aOffset;
  fnv1a_mix(h, data, size);
  return h;
}

}  // namespace tem
