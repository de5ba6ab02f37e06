// Which BLAS the process runs (CHOLMOD's supernodal factorization spends most of its time in its dense
// kernels) and how many threads it may use. Debian selects the library at run time through its
// alternatives (libblas.so.3): the reference BLAS, or OpenBLAS once libopenblas0-pthread is installed
// (scripts/install_deps.sh installs it; docs/building.md, docs/performance.md give the measured difference).
#pragma once
#include <string>

namespace iarap {

// The file the BLAS routine dgemm_ was loaded from (e.g. ".../openblas-pthread/libblas.so.3"), or
// "unknown" when no BLAS is loaded yet or the loader cannot tell.
std::string blas_library_path();

// A short name for reports: "openblas-pthread", "openblas-openmp", "reference" (Debian's libblas3),
// or the library's file name for anything else.
std::string blas_library_name();

// Caps the BLAS's own thread pool at n >= 1 threads where the library has one (OpenBLAS); a no-op for
// single-threaded BLAS. Called before each numeric factorization with the cores free at that moment, so
// that OpenBLAS's threads never outnumber them (the factorization can run beside the intrinsic build).
void limit_blas_threads(int n);

} // namespace iarap
