# Sources of the laplacian module, relative to src/.
list(APPEND IARAP_SOURCES
  laplacian/intrinsic_for_mesh.cpp laplacian/intrinsic_cotan_laplacian.cpp laplacian/iarap_laplacian.cpp
  laplacian/first_segment_laplacians.cpp laplacian/laplacians.cpp laplacian/mass_matrix.cpp
  laplacian/laplacian_properties.cpp)
