// parallel_for(n, body): body(i) for i in [0, n) on the OpenMP threads, with exceptions carried
// out of the parallel region.
//
// An exception that leaves an OpenMP region calls std::terminate, and inside MeshLab that takes
// the user's unsaved work down with it. Here every body call is wrapped: the exception of the
// lowest failing i is kept and rethrown on the calling thread after the loop, so the caller sees
// an ordinary exception, and which one does not depend on the thread count. The other iterations
// still run (OpenMP has no portable early exit); their exceptions are dropped.
//
// FirstFailure: that carrier on its own, for loops that need more than parallel_for offers
// (per-thread scratch, their own schedule). record(i, error) from inside the region (it never
// throws), rethrow() after it: the exception of the lowest i recorded.
//
// ThreadScope(threads): the OpenMP thread count for the lifetime of the object (threads > 0), the
// previous one restored after; threads <= 0 keeps the runtime's default.
//
// gather_in_ranges<T>(n, body): items 0..n-1 cut into ranges whose outputs are gathered apart on
// the threads (body(begin, end, out) appends what items [begin, end) give to `out`), joined in
// range order: the sequence one pass would give, whatever the thread count.
//
// SerialOpenMPScope: for the lifetime of the object no OpenMP region is active (max-active-levels
// 0), so a library's regions with a fixed team size run on the calling thread; restored after.
#pragma once

#include <algorithm>
#include <climits>
#include <exception>
#include <stdexcept>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace slim {

// One OpenMP runtime setting (an int read by Get, written by Set) held for the lifetime of the
// object, the previous value restored after; `hold` false leaves it alone. Without OpenMP: nothing.
template <int (*Get)(), void (*Set)(int)>
class OpenMPSettingScope {
 public:
  OpenMPSettingScope(bool hold, int value) : previous_(Get()) {
    if (hold) Set(value);
  }
  ~OpenMPSettingScope() { Set(previous_); }
  OpenMPSettingScope(const OpenMPSettingScope&) = delete;
  OpenMPSettingScope& operator=(const OpenMPSettingScope&) = delete;

 private:
  int previous_;
};

namespace omp_setting {
#ifdef _OPENMP
inline int threads() { return omp_get_max_threads(); }
inline void set_threads(int n) { omp_set_num_threads(n); }
inline int active_levels() { return omp_get_max_active_levels(); }
inline void set_active_levels(int n) { omp_set_max_active_levels(n); }
#else
inline int threads() { return 1; }
inline void set_threads(int) {}
inline int active_levels() { return 1; }
inline void set_active_levels(int) {}
#endif
}  // namespace omp_setting

class ThreadScope : OpenMPSettingScope<omp_setting::threads, omp_setting::set_threads> {
 public:
  explicit ThreadScope(int threads) : OpenMPSettingScope(threads > 0, threads) {}
};

class SerialOpenMPScope : OpenMPSettingScope<omp_setting::active_levels, omp_setting::set_active_levels> {
 public:
  SerialOpenMPScope() : OpenMPSettingScope(true, 0) {}
};

class FirstFailure {
 public:
  void record(long long i, std::exception_ptr error) noexcept {
#pragma omp critical(slim_first_failure)
    if (i < index_) {
      index_ = i;
      error_ = std::move(error);
    }
  }
  // The exception as std::invalid_argument(message); if even that cannot be made (no memory),
  // the allocation failure itself.
  void record_invalid_argument(long long i, const char* message) noexcept {
    try {
      record(i, std::make_exception_ptr(std::invalid_argument(message)));
    } catch (...) {
      record(i, std::current_exception());
    }
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  long long index_ = LLONG_MAX;
  std::exception_ptr error_;
};

// Iterations are handed out in chunks of up to 256 (cheap bodies, many of them), smaller when there
// are few: a loop over 16 ranges or 4 phases must not go to one thread as one chunk.
template <class Body>
void parallel_for(int n, Body&& body) {
  FirstFailure failure;
  const int chunk = std::max(1, std::min(256, n / (8 * omp_setting::threads())));
#pragma omp parallel for schedule(dynamic, chunk)
  for (int i = 0; i < n; ++i) {
    try {
      body(i);
    } catch (...) {
      failure.record(i, std::current_exception());
    }
  }
  failure.rethrow();
}

template <class T, class Body>
std::vector<T> gather_in_ranges(long long n, Body body) {
  const int ranges = n >= 4096 ? 16 : 1;
  std::vector<std::vector<T>> parts(static_cast<size_t>(ranges));
  parallel_for(ranges, [&](int r) { body(n * r / ranges, n * (r + 1) / ranges, parts[static_cast<size_t>(r)]); });
  size_t total = 0;
  for (const auto& p : parts) total += p.size();
  std::vector<T> out;
  out.reserve(total);
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace slim
