// The server's HTTP policy, the same for every route: who may call (Host and Origin), what a body must be
// (JSON routes take application/json, file routes anything but a form), the size limits, and the status
// each failure answers:
//   HttpError its own status; SessionConflict 409; InputError 400; TopologyError and SolverError 422;
//   anything else 500. httplib's own refusals (404, 413, a POST without Content-Length) get messages too.
#pragma once
#include "serve_config.h"

#include "iarap/solver/arap_types.h" // Eigen before httplib (see api_routes.h)

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <exception>

namespace iarap::serve {

// The status the error answers (see above).
int error_status(const std::exception& error);

// Sets the payload limit, the Host / Origin check, the exception and error handlers and the optional log.
// config must outlive the server.
void configure_server(httplib::Server& server, const ServeConfig& config);

// The JSON object of a request to a JSON route: HttpError 415 for another Content-Type, and
// parse_json_object's 400 / 413 (json_input.h) with config.max_json_bytes.
nlohmann::json json_body(const httplib::Request& req, const ServeConfig& config);

// File bodies (uploads, saved sessions) are the raw bytes with any Content-Type but a form's: a form
// encodes the bytes, and curl's default -d / --data-binary type is one. HttpError 415 otherwise.
void require_raw_file(const httplib::Request& req);

// A whole-number query parameter in [min, max], fallback when absent; HttpError 400 naming it otherwise.
long long integer_param(const httplib::Request& req, const char* name, long long fallback, long long min,
                        long long max);

// The ?method= parameter (iarap when absent); InputError for an unknown name.
ArapMethod method_param(const httplib::Request& req);

} // namespace iarap::serve
