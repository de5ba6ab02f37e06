# Sources of the io module, relative to src/.
list(APPEND IARAP_SOURCES
  io/text_reader.cpp io/face_builder.cpp io/atomic_file.cpp io/writer_support.cpp
  io/read_obj.cpp io/read_off.cpp io/read_ply.cpp io/ply_header.cpp io/ply_ascii_body.cpp
  io/ply_binary_body.cpp io/read_stl.cpp io/read_mesh.cpp
  io/tet_mesh.cpp io/read_tet_mesh.cpp io/read_tet_mesh_medit.cpp io/read_tet_mesh_tetgen.cpp
  io/read_tet_mesh_gmsh.cpp io/write_tet_mesh.cpp
  io/write_obj.cpp io/write_off.cpp io/write_ply.cpp io/write_mesh.cpp io/check_output_path.cpp io/write_png.cpp)
