list(APPEND IARAP_TEST_SOURCES laplacian/iarap_refined_laplacian_test.cpp
  laplacian/laplacians_test.cpp laplacian/mass_matrix_test.cpp laplacian/laplacian_properties_test.cpp
  laplacian/laplacian_command_test.cpp laplacian/operator_identity_test.cpp)
