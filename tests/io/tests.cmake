list(APPEND IARAP_TEST_SOURCES
  io/read_obj_test.cpp io/read_obj_textured_test.cpp io/read_off_test.cpp io/read_ply_test.cpp io/read_stl_test.cpp
  io/write_mesh_test.cpp io/read_tet_mesh_test.cpp io/shared_meshes_test.cpp io/input_quirks_test.cpp io/write_png_test.cpp)
