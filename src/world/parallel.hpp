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

}  // namespace tem
