// The viewer's UV tab: POST /api/param flattens the session's rest mesh (arap_parameterize) and answers a
// binary frame, the report as its JSON header and the map as "uv" (float32 #V x 2, row-major).
#pragma once
#include "serve_state.h"

#include <nlohmann/json.hpp>
#include <string>

namespace iarap::serve {

// body: {"energy": "triangle" | "arap" | "iarap", "boundary": "free" | "circle", "init": "lscm" | "tutte" |
// "harmonic", "allow_flips": bool, "iterations": 0..max_iterations}, every field optional (the defaults of
// `iarap param`). Throws InputError (400) for an unknown field or value, TopologyError (422) for a mesh that
// is not a disk (the message says what it has), SolverError (422).
std::string param_frame(const MeshSnapshot& rest, const nlohmann::json& body, int max_iterations);

} // namespace iarap::serve
