// Helpers for the reader and writer tests: small files written on the fly, and error-message checks.
#pragma once
#include "iarap/core/errors.h"
#include "test_support.h"

#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace iarap::test {

// Writes `bytes` to a fresh file named `name` in this process's temp folder and returns its path.
inline std::string write_temp_file(const std::string& name, const std::string& bytes) {
  const std::string path = (temp_dir("io") / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// Runs `read` and expects an InputError whose message contains every one of `parts`.
template <typename Read> void expect_input_error(Read read, std::initializer_list<std::string> parts) {
  try {
    read();
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
  }
}

} // namespace iarap::test
