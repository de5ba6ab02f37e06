# Sources of the core module, relative to src/.
list(APPEND IARAP_SOURCES core/threads.cpp core/run_beside.cpp core/version.cpp core/resident_memory.cpp
     core/blas_library.cpp)
