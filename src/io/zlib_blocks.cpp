#include "io/zlib_blocks.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "support/parallel.hpp"

namespace tem {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the header is written as the machine's UInt64s, and the files say LittleEndian");

// zlib's fastest level. Indices (connectivity, ids) and values repeated point after point (a
// body's angular velocity) shrink to a fifth or far less at any level; level 6 took twice the
// time for under 1% (docs/benchmarks.md).
constexpr int kLevel = Z_BEST_SPEED;

// An array whose first block kLevel does not shrink to half is written at level 0, zlib's stored
// blocks (still one zlib stream a block, as the format wants): the positions, velocities and
// contact forces of many bodies, doubles that differ in all but their first bytes, shrink by
// 6-23% at level 1 for most of the time a frame takes (docs/benchmarks.md). What TEM writes
// falls far on either side of the half. The choice depends on the bytes alone, so the file does.
constexpr double kWorthwhile = 0.5;

void append_uint64(std::string& out, std::uint64_t value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

void append_zlib_blocks(std::string& out, const void* bytes, std::size_t size) {
  const auto* in = static_cast<const Bytef*>(bytes);
  const std::size_t blocks = (size + kVtkBlockSize - 1) / kVtkBlockSize;
  const std::size_t bound = compressBound(kVtkBlockSize);
  // Every block gets a slot of the largest size zlib may need, so the threads never share one.
  const auto compressed =
      std::make_unique_for_overwrite<Bytef[]>(std::max<std::size_t>(1, blocks * bound));
  std::vector<uLongf> sizes(blocks);
  std::vector<int> results(blocks);
  auto compress_block = [&](std::size_t b, int level) {
    const std::size_t begin = b * kVtkBlockSize;
    sizes[b] = bound;
    results[b] = compress2(&compressed[b * bound], &sizes[b], in + begin,
                           std::min(kVtkBlockSize, size - begin), level);
  };
  // Block 0 at kLevel tells the level of the others; it is done again only at level 0.
  int level = kLevel;
  std::size_t done = 0;
  if (blocks > 0) {
    compress_block(0, kLevel);
    done = 1;
    if (static_cast<double>(sizes[0]) >
        kWorthwhile * static_cast<double>(std::min(kVtkBlockSize, size))) {
      level = Z_NO_COMPRESSION;
      done = 0;
    }
  }
  parallel_for(static_cast<long long>(blocks - done), 1,
               [&](long long k) { compress_block(done + static_cast<std::size_t>(k), level); });
  // With a buffer of compressBound's size, only memory can fail.
  for (int result : results)
    if (result != Z_OK) throw std::bad_alloc();

  append_uint64(out, blocks);
  append_uint64(out, kVtkBlockSize);
  append_uint64(out, size % kVtkBlockSize);
  for (uLongf s : sizes) append_uint64(out, s);
  for (std::size_t b = 0; b < blocks; ++b)
    out.append(reinterpret_cast<const char*>(&compressed[b * bound]), sizes[b]);
}

}  // namespace tem
