list(APPEND IARAP_TEST_SOURCES core/threads_test.cpp core/version_test.cpp core/blas_library_test.cpp)
