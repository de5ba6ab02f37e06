#include "http_reply.h"

#include "iarap/core/errors.h"

#include <httplib.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>

namespace iarap::serve {

void send_json(httplib::Response& res, const nlohmann::json& body, int status) {
  res.status = status;
  res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "application/json");
}

void send_error(httplib::Response& res, std::string message, int status) {
  if (message.size() > 600) message = message.substr(0, 600) + "... (cut)";
  send_json(res, {{"error", message}}, status);
}

void send_binary(httplib::Response& res, const std::string& body) {
  res.set_content(body, "application/octet-stream");
}

// httplib compresses text types with brotli at its highest quality whenever the client accepts it:
// three.core.js (1.4 MB) took 36 s on a loaded 2-core machine instead of 1.3 s, and compression buys
// nothing over loopback. A body given by a provider with a known length is sent as is.
void send_file(httplib::Response& res, std::string bytes, const std::string& content_type) {
  const auto body = std::make_shared<const std::string>(std::move(bytes));
  res.set_content_provider(body->size(), content_type,
                           [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             sink.write(body->data() + offset, std::min(length, body->size() - offset));
                             return true;
                           });
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read back " + path.filename().string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

} // namespace iarap::serve
