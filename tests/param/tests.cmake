# Tests of the param module (UV maps), relative to tests/.
list(APPEND IARAP_TEST_SOURCES
  param/injective_step_test.cpp param/disk_mesh_test.cpp
  param/lscm_test.cpp param/fixed_boundary_map_test.cpp param/map_distortion_test.cpp
  param/arap_parameterize_test.cpp param/write_uv_map_test.cpp param/planar_cells_test.cpp
  param/render_uv_picture_test.cpp param/uv_pins_test.cpp param/uv_problem_test.cpp
  param/uv_atlas_test.cpp param/uv_atlas_input_test.cpp param/chart_solve_test.cpp
  param/packing_bitmap_test.cpp)
# `iarap param` end to end; needs the tool built.
if(IARAP_BUILD_APP)
  list(APPEND IARAP_TEST_SOURCES param/param_command_test.cpp)
endif()
