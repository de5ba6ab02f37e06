list(APPEND IARAP_APP_SOURCES main.cpp)
list(APPEND IARAP_APP_SOURCES info_command.cpp deform_command.cpp bench_command.cpp bench_converge.cpp cpu_name.cpp
  write_text_file.cpp common/explain_error.cpp omp_wait_policy.cpp malloc_settings.cpp
  mesh_report_json.cpp same_file.cpp number_validators.cpp
  external_force_options.cpp simulate_command.cpp
  solve_option_flags.cpp solve_report_json.cpp)
list(APPEND IARAP_APP_SOURCES intrinsic_command.cpp)
list(APPEND IARAP_APP_SOURCES laplacian_command.cpp)
list(APPEND IARAP_APP_SOURCES serve_command.cpp serve/api_routes.cpp serve/json_input.cpp
  serve/binary_frame.cpp serve/static_files.cpp serve/private_temp_dir.cpp serve/scenario_files.cpp
  serve/route_table.cpp serve/frame_board.cpp serve/solve_option_json.cpp)
# The server's session model, its background refiner, HTTP policy and one file per resource's routes.
list(APPEND IARAP_APP_SOURCES serve/session.cpp serve/drag_motion.cpp serve/constraint_history.cpp serve/refine_job.cpp
  serve/shared_session.cpp serve/intrinsic_overlay.cpp serve/client_names.cpp serve/http_reply.cpp
  serve/http_policy.cpp serve/solve_request_json.cpp serve/state_json.cpp serve/mesh_routes.cpp
  serve/constraint_routes.cpp serve/solve_routes.cpp serve/frame_route.cpp serve/scenario_routes.cpp
  serve/static_route.cpp serve/request_targets.cpp serve/solver_constraints.cpp
  serve/uploaded_file.cpp serve/fit_runner.cpp serve/fit_routes.cpp)
list(APPEND IARAP_APP_SOURCES param_command.cpp common/param_report_json.cpp serve/param_route.cpp)
list(APPEND IARAP_APP_SOURCES batch_command.cpp)
list(APPEND IARAP_APP_SOURCES repair_command.cpp)
list(APPEND IARAP_APP_SOURCES register_command.cpp)
