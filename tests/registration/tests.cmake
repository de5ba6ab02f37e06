# Tests of the registration module (non-rigid ICP), relative to tests/.
list(APPEND IARAP_TEST_SOURCES registration/geometry_queries_test.cpp registration/rigid_alignment_test.cpp
  registration/register_test.cpp registration/register_cli_test.cpp)
