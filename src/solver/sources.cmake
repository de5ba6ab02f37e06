# Sources of the solver module, relative to src/.
list(APPEND IARAP_SOURCES
  solver/polar_rotation.cpp solver/sparse_cholesky.cpp solver/arap_elements.cpp
  solver/fit_rotations.cpp solver/arap_rhs.cpp solver/system_pattern.cpp solver/arap.cpp
  solver/local_global_problem.cpp solver/local_global_loops.cpp solver/anderson_acceleration.cpp
  solver/lbfgs_direction.cpp solver/visit_order.cpp solver/supernodal_solve.cpp)
