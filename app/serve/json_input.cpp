#include "json_input.h"

#include "http_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iarap::serve {

std::string short_description(const nlohmann::json& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size()) + " elements";
  if (value.is_object()) return "an object of " + std::to_string(value.size()) + " members";
  if (value.is_string()) {
    const std::string& text = value.get_ref<const std::string&>();
    return text.size() <= 32 ? nlohmann::json(text).dump()
                             : nlohmann::json(text.substr(0, 29)).dump() + "... (" +
                                   std::to_string(text.size()) + " characters)";
  }
  return value.dump(); // a number, boolean or null: short
}

void check_json_limits(const std::string& text, const JsonLimits& limits) {
  int depth = 0;
  std::size_t values = 1; // the top-level value, plus one per ',' and per '[' / '{' (an upper bound)
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (ch == '\\')
        ++i; // the escaped character cannot end the string
      else if (ch == '"')
        in_string = false;
      continue;
    }
    if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > limits.max_depth)
        throw HttpError(400, "JSON nests deeper than " + std::to_string(limits.max_depth) +
                                 " arrays / objects (at byte " + std::to_string(i) + ")");
      ++values;
    } else if (ch == ']' || ch == '}') {
      --depth;
    } else if (ch == ',') {
      ++values;
    }
    if (values > limits.max_values)
      throw HttpError(400, "JSON holds more than " + std::to_string(limits.max_values) + " values (at byte " +
                               std::to_string(i) + ")");
  }
}

nlohmann::json parse_json_object(const std::string& body, std::size_t max_bytes) {
  if (body.size() > max_bytes) {
    throw HttpError(413, "request body has " + std::to_string(body.size()) +
                             " bytes; the limit for JSON bodies is " + byte_limit_text(max_bytes));
  }
  check_json_limits(body);
  nlohmann::json object;
  try {
    object = nlohmann::json::parse(body);
  } catch (const nlohmann::json::parse_error& e) {
    throw HttpError(400, "malformed JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const nlohmann::json::exception& e) { // e.g. a number overflowing a double ("1e999")
    throw HttpError(400, std::string("malformed JSON: ") + e.what());
  }
  if (!object.is_object())
    throw HttpError(400, std::string("request body must be a JSON object, got ") + object.type_name());
  return object;
}

void require_known_fields(const nlohmann::json& object, const std::vector<std::string>& allowed) {
  for (const auto& item : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string names;
    for (const std::string& name : allowed) names += (names.empty() ? "" : ", ") + name;
    throw HttpError(400, "unknown field " + short_description(item.key()) + "; expected " + names);
  }
}

void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed) {
  require_known_fields(object, std::vector<std::string>(allowed.begin(), allowed.end()));
}

namespace {

const nlohmann::json* array_member(const nlohmann::json& object, const char* field) {
  const auto it = object.find(field);
  if (it == object.end()) return nullptr;
  if (!it->is_array()) throw HttpError(400, std::string(field) + " must be an array, got " + it->type_name());
  return &*it;
}

} // namespace

namespace {

// array's elements as ints; where names the array in errors ("fixed", "rigid_groups[1]").
Eigen::VectorXi integer_elements(const nlohmann::json& array, const std::string& name) {
  Eigen::VectorXi values(static_cast<Eigen::Index>(array.size()));
  for (std::size_t i = 0; i < array.size(); ++i) {
    const nlohmann::json& value = array[i];
    const std::string where = name + "[" + std::to_string(i) + "]";
    if (value.is_number_unsigned()) {
      if (value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throw HttpError(400, where + " = " + short_description(value) + " is too large");
    } else if (value.is_number_integer()) {
      const std::int64_t v = value.get<std::int64_t>();
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        throw HttpError(400, where + " = " + short_description(value) + " is out of the integer range");
    } else {
      throw HttpError(400, where + " must be an integer vertex index, got " + short_description(value));
    }
    values[static_cast<Eigen::Index>(i)] = static_cast<int>(value.get<std::int64_t>());
  }
  return values;
}

} // namespace

Eigen::VectorXi integer_array_field(const nlohmann::json& object, const char* field) {
  const nlohmann::json* array = array_member(object, field);
  return array == nullptr ? Eigen::VectorXi() : integer_elements(*array, field);
}

std::vector<Eigen::VectorXi> integer_array_list_field(const nlohmann::json& object, const char* field) {
  const nlohmann::json* array = array_member(object, field);
  std::vector<Eigen::VectorXi> lists;
  if (array == nullptr) return lists;
  for (std::size_t g = 0; g < array->size(); ++g) {
    const std::string where = std::string(field) + "[" + std::to_string(g) + "]";
    const nlohmann::json& list = (*array)[g];
    if (!list.is_array())
      throw HttpError(400, where + " must be an array of vertex indices, got " + short_description(list));
    lists.push_back(integer_elements(list, where));
  }
  return lists;
}

std::vector<double> number_array_field(const nlohmann::json& object, const char* field) {
  const nlohmann::json* array = array_member(object, field);
  if (array == nullptr) return {};
  std::vector<double> values(array->size());
  for (std::size_t i = 0; i < array->size(); ++i) {
    const nlohmann::json& value = (*array)[i];
    if (!value.is_number())
      throw HttpError(400, std::string(field) + "[" + std::to_string(i) + "] must be a number, got " +
                               short_description(value));
    values[i] = value.get<double>();
    if (!std::isfinite(values[i])) // "1e999" parses to inf
      throw HttpError(400, std::string(field) + "[" + std::to_string(i) + "] is not finite");
  }
  return values;
}

int integer_field(const nlohmann::json& object, const char* field, int fallback, int min, int max) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  const bool integer = it->is_number_integer() || it->is_number_unsigned();
  const double value = it->is_number() ? it->get<double>() : 0.0;
  if (!integer || value < min || value > max) {
    throw HttpError(400, std::string(field) + " must be an integer in " + std::to_string(min) + ".." +
                             std::to_string(max) + ", got " + short_description(*it));
  }
  return it->get<int>();
}

double number_field(const nlohmann::json& object, const char* field, double fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_number() || !std::isfinite(it->get<double>())) // "1e999" parses to inf
    throw HttpError(400, std::string(field) + " must be a finite number, got " + short_description(*it));
  return it->get<double>();
}

std::string string_field(const nlohmann::json& object, const char* field, const std::string& fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_string())
    throw HttpError(400, std::string(field) + " must be a string, got " + short_description(*it));
  return it->get<std::string>();
}

bool bool_field(const nlohmann::json& object, const char* field, bool fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_boolean())
    throw HttpError(400, std::string(field) + " must be true or false, got " + short_description(*it));
  return it->get<bool>();
}

} // namespace iarap::serve
