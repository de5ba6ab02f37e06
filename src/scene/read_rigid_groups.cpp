#include "iarap/scene/read_rigid_groups.h"

#include "iarap/core/errors.h"

#include "line_tokens.h"

#include <fstream>

namespace iarap {

std::vector<std::vector<int>> parse_rigid_groups(std::istream& in, const std::string& source,
                                                 int num_vertices) {
  std::vector<std::vector<int>> groups;
  std::vector<int> line_of(static_cast<size_t>(num_vertices), 0); // the line naming each vertex, 0: none
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    const std::string at = detail::where(source, number);
    const auto hash = text.find('#');
    const auto tokens = detail::tokens_of(text.substr(0, hash));
    if (tokens.empty() && hash != std::string::npos) continue; // a comment line
    if (tokens.empty())
      throw InputError(at + "empty line: each line is one rigid group, 'i j k ...' (at least 2 vertices)");
    if (tokens.size() < 2)
      throw InputError(at + "a rigid group of 1 vertex (" + tokens[0] + "); a group needs at least 2");
    std::vector<int> group;
    for (const std::string& token : tokens) {
      const long long index = detail::parse_index(token, at);
      if (index < 0 || index >= num_vertices)
        throw InputError(at + "vertex index " + token + " out of range; the mesh has " +
                         std::to_string(num_vertices) + " vertices (valid: 0.." +
                         std::to_string(num_vertices - 1) + ")");
      int& first = line_of[static_cast<size_t>(index)];
      if (first == number) throw InputError(at + "vertex " + token + " is named twice in this group");
      if (first != 0)
        throw InputError(at + "vertex " + token + " is already in the rigid group of line " +
                         std::to_string(first));
      first = number;
      group.push_back(static_cast<int>(index));
    }
    groups.push_back(std::move(group));
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(number));
  if (groups.empty()) throw InputError(source + ": no rigid group (expected lines 'i j k ...')");
  return groups;
}

std::vector<std::vector<int>> read_rigid_groups(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open rigid-groups file");
  return parse_rigid_groups(in, path, num_vertices);
}

} // namespace iarap
