#include "forces/semm_newton/blas_setup.hpp"

#include <dlfcn.h>
#include <strings.h>

#include <cstdlib>

#include "support/parallel.hpp"

namespace tem::newton {
namespace {

// An OpenBLAS function, looked up where the library is loaded: in the program's global scope,
// or in the library loaded beside this one (a Python extension's libraries are loaded locally,
// out of the global scope). Null for another BLAS.
void* openblas_function(const char* name) {
  void* f = dlsym(RTLD_DEFAULT, name);
  for (const char* library : {"libopenblas.so.0", "libblas.so.3"}) {
    if (f) break;
    if (void* handle = dlopen(library, RTLD_NOW | RTLD_NOLOAD)) {
      f = dlsym(handle, name);
      dlclose(handle);
    }
  }
  return f;
}

// CHOLMOD's supernodal factorisation calls the BLAS (dpotrf, dsyrk, dgemm, dtrsm) on its dense
// blocks. A threaded BLAS splits those among threads in blocks that depend on how many it has,
// and so rounds differently at different thread counts; TEM promises the same bits at any
// thread count, so the BLAS is held to one thread. scripts/install_deps.sh installs OpenBLAS's
// serial build, which has no threads (Debian's reference BLAS, which CHOLMOD gets otherwise,
// makes a settled 1,000-coin pile's Newton step 2.6 times as long: docs/benchmarks.md). Where
// a threaded OpenBLAS is chosen instead (Debian's alternatives prefer it where installed): its
// OpenMP build follows the caller's OpenMP thread count, which serially()
// (support/parallel.hpp) sets to one around each factorisation; its pthreads build has its own
// count, set here to one. The OpenMP build's setter also sets the calling thread's OpenMP thread
// count, which TEM's own regions use, so that count is put back.
void hold_to_one_thread() {
  using Setter = void (*)(int);
  auto* setter = reinterpret_cast<Setter>(openblas_function("openblas_set_num_threads"));
  if (!setter) return;
  const int threads = max_threads();
  setter(1);
  set_threads(threads);
}

// OpenBLAS (its DYNAMIC_ARCH builds, Debian's) picks its kernels by the CPU's model number, and
// takes its oldest x86-64 kernels (Prescott: SSE3) for a model newer than its table: OpenBLAS
// 0.3.21 on this project's machines (Xeon, family 6 model 207) did, and a settled 1,000-coin
// pile's Newton step took 1.2 times as long as with its AVX-512 kernels, the 1,000-coin pour's
// crash 1.3 times (docs/benchmarks.md, "The BLAS, and the overlap correction by Newton"). Where
// the user has not chosen the kernels (OPENBLAS_CORETYPE, OpenBLAS's own setting) and OpenBLAS
// fell back so on a CPU with AVX2 and FMA, they are chosen here by the instruction sets it has
// (as the OS enables them: __builtin_cpu_supports reads both): SkylakeX's with AVX-512 (F, CD,
// BW, DQ, VL), else Haswell's. OpenBLAS reads OPENBLAS_CORETYPE when it makes its kernel table,
// which is made again here (before any BLAS call of TEM's); the variable is removed after, so
// that child processes choose their own.
void choose_kernels() {
  using Call = void (*)();
  auto* quit = reinterpret_cast<Call>(openblas_function("gotoblas_dynamic_quit"));
  auto* init = reinterpret_cast<Call>(openblas_function("gotoblas_dynamic_init"));
  if (!quit || !init || std::getenv("OPENBLAS_CORETYPE")) return;
  if (strcasecmp(blas_kernels(), "Prescott") != 0) return;
  __builtin_cpu_init();
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
                      __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (!avx2) return;
  setenv("OPENBLAS_CORETYPE", avx512 ? "SkylakeX" : "Haswell", 1);
  quit();
  init();
  unsetenv("OPENBLAS_CORETYPE");
}

}  // namespace

void prepare_blas() {
  choose_kernels();
  hold_to_one_thread();
}

const char* blas_kernels() {
  using Name = const char* (*)();
  auto* name = reinterpret_cast<Name>(openblas_function("openblas_get_corename"));
  return name ? name() : "";
}

}  // namespace tem::newton
