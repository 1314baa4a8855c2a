// One array's bytes as VTK stores them compressed (compressor="vtkZLibDataCompressor",
// header_type="UInt64"): the bytes cut into blocks of kVtkBlockSize (the last one shorter), each
// block a zlib stream of its own, after a header of UInt64s: the number of blocks, the block
// size, the size of the last block if it is partial (0 when it is full, or there are no bytes),
// then every block's compressed size. VTK's readers (ParaView) and meshio read exactly this.
// Arrays that zlib hardly shrinks go in its stored blocks, uncompressed (zlib_blocks.cpp says
// which and why).
//
// Blocks are independent, so they are compressed side by side on OpenMP's threads
// (support/parallel.hpp): the bytes are the same for any number of threads.
#pragma once

#include <cstddef>
#include <string>

namespace tem {

// VTK's own default block size (vtkXMLWriter). Readers take the size from the header.
inline constexpr std::size_t kVtkBlockSize = 32768;

// Appends the header and the blocks of `size` bytes at `bytes` to `out`. Throws std::bad_alloc
// when zlib runs out of memory.
void append_zlib_blocks(std::string& out, const void* bytes, std::size_t size);

}  // namespace tem
