# Sources of the solver module, relative to src/, by layer (docs/architecture.md): the pieces of the
# problem, the LocalGlobalProblem oracle, stopping and line search, the optimizers, the facade.
list(APPEND IARAP_SOURCES
  solver/polar_rotation.cpp solver/closest_rotation_2d.cpp solver/sparse_cholesky.cpp solver/metis_ordering.cpp solver/supernodal_solve.cpp solver/visit_order.cpp
  solver/arap_elements.cpp solver/streamed_layout.cpp solver/fit_rotations.cpp solver/arap_rhs.cpp
  solver/system_pattern.cpp solver/constraint_layout.cpp solver/constrained_solve.cpp solver/cell_stiffness.cpp
  solver/soft_terms.cpp solver/quadratic_terms.cpp solver/hard_points.cpp solver/cover_elements.cpp
  solver/rotation_smoothing.cpp solver/free_row_system.cpp solver/local_global_problem.cpp solver/rigid_groups.cpp
  solver/rigid_group_problem.cpp solver/rotation_vector.cpp
  solver/stopping.cpp solver/line_search.cpp
  solver/plain_iteration.cpp solver/anderson_acceleration.cpp solver/anderson_iteration.cpp
  solver/lbfgs_direction.cpp solver/lbfgs_iteration.cpp solver/newton_trust_region.cpp
  solver/accelerator_history.cpp solver/hybrid_iteration.cpp
  solver/local_global_loops.cpp
  solver/arap_names.cpp solver/arap.cpp solver/arap_memory.cpp solver/tet_elements.cpp solver/arap_tets.cpp
  solver/solve_option_fields.cpp)
