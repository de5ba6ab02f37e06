#include "binary_frame.h"

#include <cstring>

namespace iarap::serve {

// Arrays are copied in host byte order; the browser reads them as little-endian typed arrays.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary frames assume a little-endian host");

void BinaryFrame::append(const std::string& name, const char* type, const void* data, std::size_t count) {
  arrays_.push_back({{"name", name}, {"type", type}, {"count", count}});
  payload_.append(static_cast<const char*>(data), 4 * count);
}

void BinaryFrame::add(const std::string& name, const std::vector<float>& values) {
  append(name, "float32", values.data(), values.size());
}

void BinaryFrame::add(const std::string& name, const std::vector<std::int32_t>& values) {
  append(name, "int32", values.data(), values.size());
}

void BinaryFrame::add(const std::string& name, const std::vector<std::uint32_t>& values) {
  append(name, "uint32", values.data(), values.size());
}

std::string BinaryFrame::encode(nlohmann::json header) const {
  header["arrays"] = arrays_;
  std::string json = header.dump();
  while ((4 + json.size()) % 4 != 0) json.push_back(' ');
  const auto length = static_cast<std::uint32_t>(json.size());
  std::string body(4, '\0');
  for (int k = 0; k < 4; ++k)
    body[static_cast<std::size_t>(k)] = static_cast<char>((length >> (8 * k)) & 0xffu);
  body += json;
  body += payload_;
  return body;
}

} // namespace iarap::serve
