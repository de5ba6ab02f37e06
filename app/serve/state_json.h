// GET /api/state's answer (also what the routes that change the session answer): the server's meshes,
// methods, limits and upload formats, and the session's mesh summary, constrained sets, soft constraints
// and constraint revision.
#pragma once
#include "serve_config.h"
#include "session.h"
#include "shared_session.h"

#include <nlohmann/json.hpp>

namespace iarap::serve {

nlohmann::json state_json(const ServeConfig& config, const Session& session);
// The same of the shared session, read under its mutex (one consistent state).
nlohmann::json state_json(const ServeConfig& config, const SharedSession& session);

} // namespace iarap::serve
