// OpenMP, where TEM has it (CMake option TEM_OPENMP), and a single thread where it does not.
// Only work whose results do not depend on how it is shared goes parallel (pairs of the narrow
// phase, bodies of the integration), so results are bit-identical with any number of threads.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace tem {

inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Sets the number of threads later parallel regions use (no effect without OpenMP).
inline void set_threads(int count) {
#ifdef _OPENMP
  if (count > 0) omp_set_num_threads(count);
#else
  (void)count;
#endif
}

// for (i = 0; i < n; ++i) f(i), shared among the threads when there are more than `serial_below`
// items and more than one thread, and a plain loop otherwise: even an OpenMP region of one
// thread costs a fraction of a microsecond, which a one-coin step (3-4 us) would notice.
// `dynamic`: items taken one by one (uneven work, such as runs of contact pairs).
template <class F>
void parallel_for(long long n, long long serial_below, F&& f, bool dynamic = false) {
#ifdef _OPENMP
  if (n > serial_below && omp_get_max_threads() > 1) {
    if (dynamic) {
#pragma omp parallel for schedule(dynamic, 1)
      for (long long i = 0; i < n; ++i) f(i);
    } else {
#pragma omp parallel for schedule(static)
      for (long long i = 0; i < n; ++i) f(i);
    }
    return;
  }
#else
  (void)serial_below;
  (void)dynamic;
#endif
  for (long long i = 0; i < n; ++i) f(i);
}

// Calls f() on the calling thread alone, with every OpenMP region inside it run by that thread:
// for libraries that share their work among OpenMP threads in ways TEM cannot allow.
//   - CHOLMOD opens regions of four threads per supernode to copy and clear columns: waking
//     them costs more than the work they share.
//   - An OpenMP build of OpenBLAS shares a BLAS call among omp_get_max_threads() threads, in
//     blocks that depend on their number, so that its sums round differently at different
//     thread counts: TEM promises the same bits at any thread count.
// Inside one of TEM's regions, nested regions already run alone and OpenBLAS runs on one thread.
// Outside, the calling thread's thread count is set to one, and the process-wide limit on active
// levels to none (so a region with a thread count of its own runs alone too): no other TEM
// thread runs then. Both are put back after.
template <class F>
void serially(F&& f) {
#ifdef _OPENMP
  if (!omp_in_parallel()) {
    const int threads = omp_get_max_threads();
    const int levels = omp_get_max_active_levels();
    omp_set_num_threads(1);
    omp_set_max_active_levels(0);
    f();
    omp_set_max_active_levels(levels);
    omp_set_num_threads(threads);
    return;
  }
#endif
  f();
}

}  // namespace tem
