// The viewer's UV tab: POST /api/param flattens the session's rest mesh (arap_parameterize) and answers a
// binary frame, the report as its JSON header and the map as "uv" (float32 #V x 2, row-major).
#pragma once
#include "session.h"

#include "iarap/param/param_options.h"

#include <nlohmann/json.hpp>
#include <string>

namespace iarap::serve {

// body: {"energy": "triangle" | "arap" | "iarap", "boundary": "free" | "circle", "init": "lscm" | "tutte" |
// "harmonic", "allow_flips": bool, and the solve options of solve_option_json.h ("iterations":
// 0..max_iterations)}, every field optional (the defaults of `iarap param`). Throws InputError or HttpError
// (400) for an unknown field or value; checked before the session is asked for its mesh.
ParamOptions parse_param_request(const nlohmann::json& body, int max_iterations);

// The frame of the rest mesh's map. Throws TopologyError (422) for a mesh that is not a disk (the message
// says what it has), SolverError (422).
std::string param_frame(const MeshSnapshot& rest, const ParamOptions& options);

} // namespace iarap::serve
