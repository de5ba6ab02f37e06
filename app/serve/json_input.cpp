#include "json_input.h"

#include "http_error.h"

#include <cmath>
#include <limits>

namespace iarap::serve {
namespace {

// A value as JSON text, cut to a length that keeps error messages readable.
std::string short_dump(const nlohmann::json& value) {
  std::string text = value.dump();
  return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

} // namespace

nlohmann::json parse_json_object(const std::string& body, std::size_t max_bytes) {
  if (body.size() > max_bytes) {
    throw HttpError(413, "request body has " + std::to_string(body.size()) +
                             " bytes; the limit for JSON is " + std::to_string(max_bytes));
  }
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

void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    bool known = false;
    for (const char* name : allowed)
      known = known || item.key() == name;
    if (!known) {
      std::string names;
      for (const char* name : allowed)
        names += (names.empty() ? "" : ", ") + std::string(name);
      throw HttpError(400, "unknown field \"" + item.key() + "\"; expected " + names);
    }
  }
}

namespace {

const nlohmann::json* array_member(const nlohmann::json& object, const char* field) {
  const auto it = object.find(field);
  if (it == object.end())
    return nullptr;
  if (!it->is_array())
    throw HttpError(400, std::string(field) + " must be an array, got " + it->type_name());
  return &*it;
}

} // namespace

Eigen::VectorXi integer_array_field(const nlohmann::json& object, const char* field) {
  const nlohmann::json* array = array_member(object, field);
  if (array == nullptr)
    return {};
  Eigen::VectorXi values(static_cast<Eigen::Index>(array->size()));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const nlohmann::json& value = (*array)[i];
    const std::string where = std::string(field) + "[" + std::to_string(i) + "]";
    if (value.is_number_unsigned()) {
      if (value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throw HttpError(400, where + " = " + short_dump(value) + " is too large");
    } else if (value.is_number_integer()) {
      const std::int64_t v = value.get<std::int64_t>();
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        throw HttpError(400, where + " = " + short_dump(value) + " is out of the integer range");
    } else {
      throw HttpError(400, where + " must be an integer vertex index, got " + short_dump(value));
    }
    values[static_cast<Eigen::Index>(i)] = static_cast<int>(value.get<std::int64_t>());
  }
  return values;
}

std::vector<double> number_array_field(const nlohmann::json& object, const char* field) {
  const nlohmann::json* array = array_member(object, field);
  if (array == nullptr)
    return {};
  std::vector<double> values(array->size());
  for (std::size_t i = 0; i < array->size(); ++i) {
    const nlohmann::json& value = (*array)[i];
    if (!value.is_number())
      throw HttpError(400, std::string(field) + "[" + std::to_string(i) + "] must be a number, got " +
                               short_dump(value));
    values[i] = value.get<double>();
    if (!std::isfinite(values[i])) // "1e999" parses to inf
      throw HttpError(400, std::string(field) + "[" + std::to_string(i) + "] is not finite");
  }
  return values;
}

int integer_field(const nlohmann::json& object, const char* field, int fallback, int min, int max) {
  const auto it = object.find(field);
  if (it == object.end())
    return fallback;
  const bool integer = it->is_number_integer() || it->is_number_unsigned();
  const double value = it->is_number() ? it->get<double>() : 0.0;
  if (!integer || value < min || value > max) {
    throw HttpError(400, std::string(field) + " must be an integer in " + std::to_string(min) + ".." +
                             std::to_string(max) + ", got " + short_dump(*it));
  }
  return it->get<int>();
}

double number_field(const nlohmann::json& object, const char* field, double fallback) {
  const auto it = object.find(field);
  if (it == object.end())
    return fallback;
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    throw HttpError(400, std::string(field) + " must be a finite number, got " + short_dump(*it));
  return it->get<double>();
}

std::string string_field(const nlohmann::json& object, const char* field, const std::string& fallback) {
  const auto it = object.find(field);
  if (it == object.end())
    return fallback;
  if (!it->is_string())
    throw HttpError(400, std::string(field) + " must be a string, got " + short_dump(*it));
  return it->get<std::string>();
}

bool bool_field(const nlohmann::json& object, const char* field, bool fallback) {
  const auto it = object.find(field);
  if (it == object.end())
    return fallback;
  if (!it->is_boolean())
    throw HttpError(400, std::string(field) + " must be true or false, got " + short_dump(*it));
  return it->get<bool>();
}

} // namespace iarap::serve
