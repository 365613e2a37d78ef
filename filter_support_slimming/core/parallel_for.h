// parallel_for(n, body): body(i) for i in [0, n) on the OpenMP threads, with exceptions carried
// out of the parallel region.
//
// An exception that leaves an OpenMP region calls std::terminate, and inside MeshLab that takes
// the user's unsaved work down with it. Here every body call is wrapped: the exception of the
// lowest failing i is kept and rethrown on the calling thread after the loop, so the caller sees
// an ordinary exception, and which one does not depend on the thread count. The other iterations
// still run (OpenMP has no portable early exit); their exceptions are dropped.
//
// ThreadScope(threads): the OpenMP thread count for the lifetime of the object (threads > 0), the
// previous one restored after; threads <= 0 keeps the runtime's default.
//
// SerialOpenMPScope: for the lifetime of the object no OpenMP region is active (max-active-levels
// 0), so a library's regions with a fixed team size run on the calling thread; restored after.
#pragma once

#include <exception>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace slim {

class ThreadScope {
 public:
  explicit ThreadScope(int threads) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    if (threads > 0) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~ThreadScope() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int previous_ = 1;
};

class SerialOpenMPScope {
 public:
  SerialOpenMPScope() {
#ifdef _OPENMP
    previous_ = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
#endif
  }
  ~SerialOpenMPScope() {
#ifdef _OPENMP
    omp_set_max_active_levels(previous_);
#endif
  }
  SerialOpenMPScope(const SerialOpenMPScope&) = delete;
  SerialOpenMPScope& operator=(const SerialOpenMPScope&) = delete;

 private:
  int previous_ = 1;
};

template <class Body>
void parallel_for(int n, Body&& body) {
  int first_failure = n;
  std::exception_ptr error;
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < n; ++i) {
    try {
      body(i);
    } catch (...) {
#pragma omp critical(slim_parallel_for_error)
      if (i < first_failure) {
        first_failure = i;
        error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace slim
