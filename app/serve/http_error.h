// An HTTP request the server refuses, with the status code to answer (4xx) and a message naming the field.
#pragma once
#include "iarap/core/errors.h"

#include <cstddef>
#include <sstream>
#include <string>

namespace iarap::serve {

class HttpError : public InputError {
public:
  HttpError(int status, const std::string& message) : InputError(message), status_(status) {}
  int status() const { return status_; }

private:
  int status_;
};

// A size limit for messages: "16 MiB (16777216 bytes)".
inline std::string byte_limit_text(std::size_t bytes) {
  std::ostringstream text;
  text << static_cast<double>(bytes) / (1 << 20) << " MiB (" << bytes << " bytes)";
  return text.str();
}

} // namespace iarap::serve
