// Checked reading of JSON request bodies: every failure is an HttpError 400 (413 when too large) whose
// message names the field and, for arrays, the position at fault.
#pragma once
#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

namespace iarap::serve {

// Bounds on a JSON text checked before it is parsed: nlohmann's parser recurses once per nesting level
// (100,000 nested arrays overflowed the stack) and builds a 16-byte node per value.
struct JsonLimits {
  int max_depth = 32;                            // the API's bodies nest 2 levels, scenario files 5
  std::size_t max_values = std::size_t{1} << 22; // 4M values: a selection of every vertex of a 4M-vertex mesh
};

// One pass over text without recursion: throws HttpError 400 naming the limit (and the byte where it is
// passed) when arrays / objects nest deeper than limits.max_depth or the text holds more values than
// limits.max_values. Strings are skipped, escapes included; malformed text is left to the parser.
void check_json_limits(const std::string& text, const JsonLimits& limits = {});

// Parses body as one JSON object. Throws HttpError 413 when body exceeds max_bytes, 400 when it passes
// check_json_limits' bounds, is not JSON (with the parser's byte position) or not an object.
nlohmann::json parse_json_object(const std::string& body, std::size_t max_bytes);

// A value for an error message, never longer than about 40 characters and never dumped whole: scalars
// as JSON text (long strings cut before they are quoted), arrays and objects by kind and size.
std::string short_description(const nlohmann::json& value);

// Throws HttpError 400 naming the first member of object that is not in allowed (catches typos).
void require_known_fields(const nlohmann::json& object, const std::vector<std::string>& allowed);
void require_known_fields(const nlohmann::json& object, std::initializer_list<const char*> allowed);

// object[field] as a list of integers (any value range: range checks need the mesh, see Session);
// an absent field gives an empty list. Throws 400 for a non-array, a non-integer element (naming its
// position) or an element outside the int range.
Eigen::VectorXi integer_array_field(const nlohmann::json& object, const char* field);
// object[field] as a list of integer lists (e.g. rigid_groups: [[0, 1], [5, 6, 7]]), checked as
// integer_array_field's elements, errors naming the position (rigid_groups[1][2]); absent: none.
std::vector<Eigen::VectorXi> integer_array_list_field(const nlohmann::json& object, const char* field);

// object[field] as finite numbers. Throws 400 for a non-array, a non-number or non-finite element (naming
// its position). An absent field gives an empty list.
std::vector<double> number_array_field(const nlohmann::json& object, const char* field);

// object[field] as an integer in [min, max], fallback when absent; 400 otherwise.
int integer_field(const nlohmann::json& object, const char* field, int fallback, int min, int max);

// object[field] as a finite number, fallback when absent; 400 otherwise (ranges: the caller's, which knows
// what the number means).
double number_field(const nlohmann::json& object, const char* field, double fallback);

// object[field] as a string, fallback when absent; 400 otherwise.
std::string string_field(const nlohmann::json& object, const char* field, const std::string& fallback);

// object[field] as a boolean, fallback when absent; 400 otherwise.
bool bool_field(const nlohmann::json& object, const char* field, bool fallback);

} // namespace iarap::serve
