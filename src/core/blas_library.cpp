#include "iarap/core/blas_library.h"

#include <dlfcn.h>

namespace iarap {

namespace {
// Looked up by name, not linked: the project builds against the BLAS interface only, and the library
// behind it is the system's choice.
void* blas_symbol(const char* name) {
  return ::dlsym(RTLD_DEFAULT, name);
}
} // namespace

std::string blas_library_path() {
  void* dgemm = blas_symbol("dgemm_");
  Dl_info info{};
  if (dgemm == nullptr || ::dladdr(dgemm, &info) == 0 || info.dli_fname == nullptr) return "unknown";
  return info.dli_fname;
}

std::string blas_library_name() {
  const std::string path = blas_library_path();
  if (path == "unknown") return path;
  for (const char* variant : {"openblas-pthread", "openblas-openmp", "openblas-serial"})
    if (path.find(variant) != std::string::npos) return variant;
  if (path.find("openblas") != std::string::npos) return "openblas";
  if (path.find("/blas/") != std::string::npos) return "reference";
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

void limit_blas_threads(int n) {
  using SetThreads = void (*)(int);
  static const auto set_threads = reinterpret_cast<SetThreads>(blas_symbol("openblas_set_num_threads"));
  if (set_threads != nullptr) set_threads(n < 1 ? 1 : n);
}

} // namespace iarap
