// How the routes write a response: JSON (errors included), binary frames and files.
#pragma once
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace httplib {
struct Response;
}

namespace iarap::serve {

// body as JSON; invalid UTF-8 (a client's bytes quoted in a parser's message) becomes U+FFFD: a strict dump
// would throw inside the exception handler and end the process.
void send_json(httplib::Response& res, const nlohmann::json& body, int status = 200);
// {"error": message} with status; messages may quote client data, so at most 600 characters go back.
void send_error(httplib::Response& res, std::string message, int status);
// A binary frame (binary_frame.h) or raw array, as application/octet-stream.
void send_binary(httplib::Response& res, const std::string& body);
// A file's bytes as they are, never compressed (see http_reply.cpp).
void send_file(httplib::Response& res, std::string bytes, const std::string& content_type);

// The bytes of a file the server wrote or serves; Error when it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

template <class T> std::string raw_bytes(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

} // namespace iarap::serve
