# Sources of the scene module, relative to src/.
list(APPEND IARAP_SOURCES scene/line_tokens.cpp scene/read_forces.cpp scene/read_stiffness.cpp scene/read_rigid_groups.cpp scene/read_constraints.cpp scene/region.cpp scene/scenario.cpp scene/read_scenario.cpp
  scene/remap_constraints.cpp scene/remap_scenario.cpp)
