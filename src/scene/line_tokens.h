// Tokens of the line formats of src/scene (constraints and forces files): "path:line: " prefixes, blank
// separated tokens, exact integer and finite-number parsing with messages naming the token.
#pragma once
#include <string>
#include <vector>

namespace iarap::detail {

// "source:line: ".
std::string where(const std::string& source, int line);

// Splits a line (comment already removed) into blank-separated tokens.
std::vector<std::string> tokens_of(const std::string& text);

// The whole token as an integer; InputError "at bad vertex index 'token' ..." otherwise.
long long parse_index(const std::string& token, const std::string& at);

// The whole token as a finite number; InputError "at bad NAME coordinate ..." / "non-finite NAME ...".
double parse_coordinate(const std::string& token, const std::string& at, const char* name);

} // namespace iarap::detail
