// parallel_for(n, body): body(i) for i in [0, n) on the OpenMP threads, with exceptions carried
// out of the parallel region.
//
// An exception that leaves an OpenMP region calls std::terminate, and inside MeshLab that takes
// the user's unsaved work down with it. Here every body call is wrapped: the exception of the
// lowest failing i is kept and rethrown on the calling thread after the loop, so the caller sees
// an ordinary exception, and which one does not depend on the thread count. The other iterations
// still run (OpenMP has no portable early exit); their exceptions are dropped.
#pragma once

#include <exception>

namespace slim {

template <class Body>
void parallel_for(int n, Body&& body) {
  int first_failure = n;
  std::exception_ptr error;
#pragma omp parallel for schedule(static)
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
