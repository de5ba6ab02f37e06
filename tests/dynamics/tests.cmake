# Tests of the dynamics module, relative to tests/.
list(APPEND IARAP_TEST_SOURCES dynamics/simulation_test.cpp dynamics/simulation_report_test.cpp
  dynamics/external_forces_test.cpp)
# The simulate command's report runs the tool.
if(IARAP_BUILD_APP)
  list(APPEND IARAP_TEST_SOURCES dynamics/simulate_report_cli_test.cpp)
endif()
