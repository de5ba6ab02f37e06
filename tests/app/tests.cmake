# End-to-end tests of the iarap tool; they need the tool built.
if(IARAP_BUILD_APP)
  list(APPEND IARAP_TEST_SOURCES app/cli_test.cpp app/robustness_cli_test.cpp app/explain_error_test.cpp app/simulate_cli_test.cpp
    app/repair_cli_test.cpp app/solve_option_flags_test.cpp app/tet_deform_cli_test.cpp
    ../app/common/explain_error.cpp)
endif()
