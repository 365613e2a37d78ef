#include "core/platform/blas_threads.h"

#include <dlfcn.h>

#include <vector>

namespace slim {

namespace {

struct OpenBlasThreads {
  int (*get)() = nullptr;
  void (*set)(int) = nullptr;
};

const OpenBlasThreads& openblas_threads() {
  static const OpenBlasThreads api = [] {
    OpenBlasThreads a;
    std::vector<void*> scopes = {RTLD_DEFAULT};
    for (const char* name : {"libopenblas.so.0", "libopenblas.so"})
      if (void* h = dlopen(name, RTLD_LAZY | RTLD_NOLOAD)) scopes.push_back(h);  // never loads
    for (void* scope : scopes) {
      a.get = reinterpret_cast<int (*)()>(dlsym(scope, "openblas_get_num_threads"));
      a.set = reinterpret_cast<void (*)(int)>(dlsym(scope, "openblas_set_num_threads"));
      if (a.get && a.set) return a;
    }
    return OpenBlasThreads{};
  }();
  return api;
}

}  // namespace

BlasThreadsScope::BlasThreadsScope(int threads) {
  const OpenBlasThreads& api = openblas_threads();
  if (threads <= 0 || !api.set) return;
  previous_ = api.get();
  if (previous_ == threads) return;
  set_ = api.set;
  set_(threads);
}

BlasThreadsScope::~BlasThreadsScope() {
  if (set_) set_(previous_);
}

}  // namespace slim
