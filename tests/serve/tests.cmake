# Unit tests of the server behind `iarap serve` (app/serve/): its session model, static files and JSON
# input, compiled with the server's files they test (no HTTP: tests/web drives the routes).
if(IARAP_BUILD_APP)
  list(APPEND IARAP_TEST_SOURCES serve/session_test.cpp serve/shared_session_test.cpp
    serve/planar_session_test.cpp serve/static_files_test.cpp serve/json_input_test.cpp
    serve/serve_test_meshes.cpp serve/soft_handle_test.cpp serve/fit_runner_test.cpp serve/tet_session_test.cpp
    serve/refine_job_test.cpp serve/drag_motion_test.cpp ../app/serve/drag_motion.cpp
    ../app/serve/session.cpp ../app/serve/request_targets.cpp ../app/serve/solver_constraints.cpp ../app/serve/fit_runner.cpp ../app/serve/constraint_history.cpp
    ../app/serve/refine_job.cpp ../app/serve/shared_session.cpp ../app/serve/intrinsic_overlay.cpp
    ../app/serve/frame_board.cpp ../app/serve/json_input.cpp ../app/serve/static_files.cpp
    ../app/serve/solve_option_json.cpp ../app/serve/solve_request_json.cpp ../app/common/explain_error.cpp)
endif()
# ctest also runs them as one test whose name says "serve" (ctest -R serve), beside the discovered ones.
if(IARAP_BUILD_APP)
  add_test(NAME serve_unit_tests COMMAND iarap_tests --gtest_filter=Serve*)
  set_tests_properties(serve_unit_tests PROPERTIES TIMEOUT 600)
endif()
