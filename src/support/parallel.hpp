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

}  // namespace tem
