# Tests of the dynamics module, relative to tests/.
list(APPEND IARAP_TEST_SOURCES dynamics/simulation_test.cpp dynamics/external_forces_test.cpp)
