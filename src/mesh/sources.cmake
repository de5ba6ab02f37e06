# Sources of the mesh module, relative to src/.
list(APPEND IARAP_SOURCES mesh/edge_topology.cpp mesh/face_index_range.cpp mesh/cotan.cpp
  mesh/connected_components.cpp mesh/weld_representatives.cpp
  mesh/validate.cpp mesh/check_coordinates.cpp mesh/check_face_indices.cpp mesh/check_zero_area_faces.cpp mesh/degenerate_face.cpp mesh/deform_needs.cpp
  mesh/check_edge_manifold.cpp mesh/count_non_delaunay_edges.cpp mesh/check_orientation.cpp
  mesh/check_vertex_manifold.cpp mesh/check_components.cpp
  mesh/corner_fans.cpp mesh/face_orientation.cpp mesh/split_non_manifold.cpp
  mesh/repair.cpp mesh/subdivide.cpp mesh/normalize_scale.cpp)
