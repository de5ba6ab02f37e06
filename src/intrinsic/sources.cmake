# Sources of the intrinsic module, relative to src/.
list(APPEND IARAP_SOURCES
  intrinsic/signpost_triangulation.cpp
  intrinsic/trace_edges.cpp
  intrinsic/segments.cpp
  intrinsic/tufted_cover.cpp
  intrinsic/intrinsic_delaunay.cpp)
