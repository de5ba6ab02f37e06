// Tokens of the line formats of src/scene (constraints and forces files): "path:line: " prefixes, blank
// separated tokens, exact integer and finite-number parsing with messages naming the token.
#pragma once
#include <functional>
#include <istream>
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

// Reads the per-vertex lines of in ('#' comments and blank lines skipped): each must have `count` tokens
// (InputError "at expected 'format' ..." otherwise) and start with a vertex index in 0..num_vertices-1
// (the message gives the mesh size). Calls line(index, tokens, at, line number) for each; returns how
// many there were. A read error throws naming the last line read.
int for_each_vertex_line(
    std::istream& in, const std::string& source, int num_vertices, size_t count, const char* format,
    const std::function<void(int, const std::vector<std::string>&, const std::string&, int)>& line);

} // namespace iarap::detail
