list(APPEND IARAP_APP_SOURCES main.cpp)
list(APPEND IARAP_APP_SOURCES info_command.cpp deform_command.cpp bench_command.cpp bench_converge.cpp cpu_name.cpp
  write_text_file.cpp common/explain_error.cpp omp_wait_policy.cpp malloc_settings.cpp
  mesh_report_json.cpp same_file.cpp number_validators.cpp
  external_force_options.cpp simulate_command.cpp
  solve_option_flags.cpp solve_report_json.cpp)
list(APPEND IARAP_APP_SOURCES intrinsic_command.cpp)
list(APPEND IARAP_APP_SOURCES laplacian_command.cpp)
list(APPEND IARAP_APP_SOURCES serve_command.cpp serve/api_routes.cpp serve/serve_state.cpp serve/json_input.cpp
  serve/binary_frame.cpp serve/static_files.cpp serve/private_temp_dir.cpp serve/scenario_files.cpp
  serve/route_table.cpp serve/frame_board.cpp serve/solve_option_json.cpp)
list(APPEND IARAP_APP_SOURCES param_command.cpp common/param_report_json.cpp serve/param_route.cpp)
list(APPEND IARAP_APP_SOURCES batch_command.cpp)
list(APPEND IARAP_APP_SOURCES repair_command.cpp)
list(APPEND IARAP_APP_SOURCES register_command.cpp)
