// POST /api/solve's body read into a SolveRequest: the solve options by their schema names
// (solve_option_json.h) and the server's own fields (method, transform / handle_targets, cell_energy,
// refine, refine_accelerator, gravity, density, forces). Every failure is an HttpError 400 or InputError
// naming the field; what needs the mesh (indices, counts against #V) is checked by Session::solve.
#pragma once
#include "solve_request.h"

#include <nlohmann/json.hpp>

namespace iarap::serve {

// The server holds a request to at least one iteration and at most max_iterations (limits.max_iterations
// of /api/state).
SolveRequest parse_solve_request(const nlohmann::json& body, int max_iterations);

// The part of a solve request that says where the constrained vertices go (POST /api/scenario): only
// method and transform or handle_targets.
SolveRequest parse_target_request(const nlohmann::json& body, int max_iterations);

} // namespace iarap::serve
