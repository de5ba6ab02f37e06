# Sources of the mesh module, relative to src/.
list(APPEND IARAP_SOURCES mesh/edge_topology.cpp mesh/cotan.cpp mesh/connected_components.cpp
  mesh/validate.cpp mesh/repair.cpp mesh/subdivide.cpp
  mesh/normalize_scale.cpp)
