// BlasThreadsScope(threads): OpenBLAS's thread count held at `threads` for the lifetime of the
// object and restored after (threads <= 0, or a BLAS that is not OpenBLAS: nothing is changed).
//
// Why: OpenBLAS splits its kernels across threads, and the split changes the rounding: CHOLMOD's
// supernodal factorization gave different bits with OPENBLAS_NUM_THREADS=1 and 2 (the same count
// always repeats exactly). The optimizer's stopping rule reads statistics that must repeat, so the
// global step holds BLAS at one thread around CHOLMOD's calls. One thread also keeps OpenBLAS's
// workers from spinning on the second core after the factorization, which slowed the first
// iterations' OpenMP loops.
//
// The functions are looked up at run time: they exist only when the BLAS behind CHOLMOD is
// OpenBLAS. A plugin's dependencies are loaded with RTLD_LOCAL and are invisible to RTLD_DEFAULT,
// so the already-loaded library is asked too (never loaded by this).
#pragma once

namespace slim {

class BlasThreadsScope {
 public:
  explicit BlasThreadsScope(int threads);
  ~BlasThreadsScope();
  BlasThreadsScope(const BlasThreadsScope&) = delete;
  BlasThreadsScope& operator=(const BlasThreadsScope&) = delete;

 private:
  void (*set_)(int) = nullptr;
  int previous_ = 0;
};

}  // namespace slim
