list(APPEND IARAP_TEST_SOURCES fuzz/reader_fuzz_test.cpp fuzz/pipeline_fuzz_test.cpp)
