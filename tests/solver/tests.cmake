# Tests of the solver module, relative to tests/.
list(APPEND IARAP_TEST_SOURCES
  solver/polar_rotation_test.cpp solver/sparse_cholesky_test.cpp solver/metis_ordering_test.cpp solver/arap_elements_test.cpp
  solver/arap_test.cpp solver/boundary_refine_test.cpp solver/system_pattern_test.cpp
  solver/fit_rotations_test.cpp solver/visit_order_test.cpp
  solver/accelerated_solve_test.cpp solver/supernodal_solve_test.cpp solver/planar_arap_test.cpp
  solver/closest_rotation_2d_test.cpp solver/stopping_test.cpp
  solver/unreferenced_vertices_test.cpp solver/soft_constraints_test.cpp solver/newton_warm_start_test.cpp
  solver/hard_points_test.cpp solver/solve_option_fields_test.cpp solver/stiffness_test.cpp solver/arap_memory_test.cpp
  solver/tet_arap_test.cpp solver/rotation_smoothing_test.cpp solver/rigid_groups_test.cpp
  solver/accelerator_history_test.cpp)
