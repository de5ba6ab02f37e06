list(APPEND IARAP_TEST_SOURCES fuzz/reader_fuzz_test.cpp)
