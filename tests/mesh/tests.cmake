list(APPEND IARAP_TEST_SOURCES mesh/validate_test.cpp mesh/repair_test.cpp mesh/subdivide_test.cpp
  mesh/edge_topology_test.cpp mesh/weld_representatives_test.cpp mesh/face_index_range_test.cpp
  mesh/robustness_suite_test.cpp mesh/deform_needs_test.cpp)
