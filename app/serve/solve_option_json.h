// The solve options of a request body (POST /api/solve): each field of iarap/solver/solve_option_fields.h
// by its canonical name, read with the library's parser and refused with its message.
#pragma once
#include "iarap/solver/arap_types.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace iarap::serve {

// The canonical names of the solve options, in the schema's order (the fields a body may set).
std::vector<std::string> solve_option_names();

// Sets the member of `options` of each solve option `body` names. Throws HttpError 400 with the library's
// message ("tolerance must be a finite number; got \"small\"") for a value of the wrong type or range.
void read_solve_options(const nlohmann::json& body, ArapSolveOptions& options);

} // namespace iarap::serve
