// The BLAS under CHOLMOD's supernodal factorisation (island_factor.hpp): set up once, before the
// first factorisation, so that it gives the same bits at any thread count and runs the kernels
// the CPU has (blas_setup.cpp says why each step is needed).
#pragma once

namespace tem::newton {

// Holds a threaded OpenBLAS to one thread, and where OpenBLAS did not recognise the CPU and fell
// back to its oldest x86-64 kernels, chooses them by the CPU's instruction sets. Does nothing
// for another BLAS. Not safe beside other BLAS calls in the process: call it once, before the
// first (island_factor.cpp does, under std::call_once).
void prepare_blas();

// The kernels OpenBLAS runs ("SkylakeX", "Haswell", "Prescott", ...), or "" for another BLAS.
const char* blas_kernels();

}  // namespace tem::newton
