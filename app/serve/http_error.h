// An HTTP request the server refuses, with the status code to answer (4xx) and a message naming the field.
#pragma once
#include "iarap/core/errors.h"

#include <string>

namespace iarap::serve {

class HttpError : public InputError {
public:
  HttpError(int status, const std::string& message) : InputError(message), status_(status) {}
  int status() const { return status_; }

private:
  int status_;
};

} // namespace iarap::serve
