list(APPEND IARAP_TEST_SOURCES scene/read_constraints_test.cpp scene/region_test.cpp scene/scenario_test.cpp
  scene/read_scenario_test.cpp scene/remap_constraints_test.cpp scene/bundled_scenarios_test.cpp
  scene/remap_scenario_test.cpp scene/read_stiffness_test.cpp scene/read_rigid_groups_test.cpp)
