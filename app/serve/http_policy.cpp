#include "http_policy.h"

#include "client_names.h"
#include "http_error.h"
#include "http_reply.h"
#include "json_input.h"
#include "session.h"

#include "iarap/core/errors.h"

#include <algorithm>
#include <charconv>
#include <iostream>

namespace iarap::serve {
namespace {

const char* const json_type_hint = "this route takes a JSON body with Content-Type: application/json "
                                   "(curl: -H 'Content-Type: application/json')";
const char* const raw_file_hint =
    "send the file's bytes as the body with a Content-Type other than a form's, "
    "e.g. curl --data-binary @mesh.off -H 'Content-Type: application/octet-stream'";

bool is_form(const std::string& content_type) {
  return content_type.rfind("application/x-www-form-urlencoded", 0) == 0 ||
         content_type.rfind("multipart/form-data", 0) == 0;
}

void answer_exception(httplib::Response& res, std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    const int status = error_status(e);
    send_error(res, status == 500 ? std::string("internal error: ") + e.what() : std::string(e.what()),
               status);
  } catch (...) {
    send_error(res, "internal error", 500);
  }
}

// Refuses requests from other web pages (Origin) and from DNS-rebound names (Host).
httplib::Server::HandlerResponse check_origin(const ServeConfig& config, const httplib::Request& req,
                                              httplib::Response& res) {
  const std::string host = req.get_header_value("Host");
  if (!config.allowed_hosts.empty() && std::find(config.allowed_hosts.begin(), config.allowed_hosts.end(),
                                                 host) == config.allowed_hosts.end()) {
    send_json(res, {{"error", "Host \"" + safe_label(host) + "\" is not this server's address"}}, 403);
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.has_header("Origin") && req.get_header_value("Origin") != "http://" + host) {
    send_json(res, {{"error", "cross-origin requests are refused"}}, 403);
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

// The message of an error status httplib answers itself (no handler ran): 404, 413 with the limit of the
// route, and 415 for a form body httplib refused as too large for a form (8 KiB) when it is within the
// route's limit (curl --data-binary sends a form's type unless told otherwise).
httplib::Server::HandlerResponse answer_transport_error(const ServeConfig& config,
                                                        const httplib::Request& req, httplib::Response& res) {
  if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
  const bool upload = req.path == "/api/upload";
  const std::size_t limit = upload ? config.max_upload_bytes : config.max_json_bytes;
  std::string message = "HTTP " + std::to_string(res.status);
  if (res.status == 404) {
    message = "not found: " + safe_label(req.path);
  } else if (res.status == 400) {
    // httplib refuses a POST without Content-Length (e.g. `curl -X POST URL`) before any route runs.
    message =
        "malformed HTTP request: a " + safe_label(req.method) +
        " needs a Content-Length header (send a body, e.g. curl -d '{}' -H 'Content-Type: application/json')";
  } else if (res.status == 413) {
    const std::string length = req.get_header_value("Content-Length");
    const bool within = !length.empty() && length.size() < 19 &&
                        length.find_first_not_of("0123456789") == std::string::npos &&
                        std::stoull(length) <= limit;
    if (is_form(req.get_header_value("Content-Type")) && within) {
      res.status = 415;
      message = upload || req.path == "/api/scenario/load" ? raw_file_hint : json_type_hint;
    } else {
      message = std::string("request body too large; the limit for ") +
                (upload ? "mesh uploads" : "JSON bodies and scenario files") + " is " +
                byte_limit_text(limit);
    }
  }
  send_error(res, message, res.status);
  return httplib::Server::HandlerResponse::Handled;
}

} // namespace

int error_status(const std::exception& error) {
  if (const auto* http = dynamic_cast<const HttpError*>(&error)) return http->status();
  if (dynamic_cast<const SessionConflict*>(&error)) return 409;
  if (dynamic_cast<const InputError*>(&error)) return 400;
  if (dynamic_cast<const TopologyError*>(&error) || dynamic_cast<const SolverError*>(&error)) return 422;
  return 500;
}

void configure_server(httplib::Server& server, const ServeConfig& config) {
  server.set_payload_max_length(std::max(config.max_json_bytes, config.max_upload_bytes));
  server.set_pre_routing_handler([&config](const httplib::Request& req, httplib::Response& res) {
    return check_origin(config, req, res);
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
    answer_exception(res, error);
  });
  // Named type: a lambda alone is ambiguous between the two set_error_handler overloads.
  const httplib::Server::HandlerWithResponse error_handler = [&config](const httplib::Request& req,
                                                                       httplib::Response& res) {
    return answer_transport_error(config, req, res);
  };
  server.set_error_handler(error_handler);
  if (config.verbose) {
    server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
      std::cerr << "serve: " << req.method << " " << req.path << " -> " << res.status << "\n";
    });
  }
}

// JSON routes take Content-Type application/json, which a form on another web page cannot send without
// a CORS preflight; curl's -d default (a form) is told what to send instead.
nlohmann::json json_body(const httplib::Request& req, const ServeConfig& config) {
  const std::string type = req.get_header_value("Content-Type");
  if (type.rfind("application/json", 0) != 0) {
    throw HttpError(415, std::string(json_type_hint) + "; got " +
                             (type.empty() ? std::string("none") : "\"" + safe_label(type) + "\""));
  }
  return parse_json_object(req.body, config.max_json_bytes);
}

void require_raw_file(const httplib::Request& req) {
  if (is_form(req.get_header_value("Content-Type"))) throw HttpError(415, raw_file_hint);
}

long long integer_param(const httplib::Request& req, const char* name, long long fallback, long long min,
                        long long max) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < min || value > max)
    throw HttpError(400, std::string(name) + " must be a whole number from " + std::to_string(min) + " to " +
                             std::to_string(max) + ", got \"" + safe_label(text) + "\"");
  return value;
}

ArapMethod method_param(const httplib::Request& req) {
  return parse_arap_method(req.has_param("method") ? req.get_param_value("method") : "iarap");
}

} // namespace iarap::serve
