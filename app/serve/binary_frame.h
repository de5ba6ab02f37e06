// One HTTP body carrying a JSON header and typed arrays, so a solve answers in one round trip:
//   uint32 little-endian J | J bytes of JSON | spaces up to a multiple of 4 | the arrays back to back.
// The JSON lists the arrays under "arrays": [{"name", "type" ("float32" | "int32" | "uint32"), "count"}],
// in order, so the browser can wrap each as a typed array view without copying.
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace iarap::serve {

class BinaryFrame {
public:
  void add(const std::string& name, const std::vector<float>& values);
  void add(const std::string& name, const std::vector<std::int32_t>& values);
  void add(const std::string& name, const std::vector<std::uint32_t>& values);
  // header gets the "arrays" member; returns the whole body.
  std::string encode(nlohmann::json header) const;

private:
  void append(const std::string& name, const char* type, const void* data, std::size_t count);
  nlohmann::json arrays_ = nlohmann::json::array();
  std::string payload_;
};

} // namespace iarap::serve
